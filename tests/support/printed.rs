//! Lines a program printed, read as text and numbers.

/// A piece of a printed line: a number, or any other character (a run of
/// white space as one space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Token {
    /// A number.
    Number(f64),
    /// Any other character.
    Text(char),
}

/// The tokens of `text`: a number is an optional sign, digits with an
/// optional fraction and exponent, not preceded by a letter, digit, `_` or
/// `.` (so `a1` and `x2` stay names).
pub fn tokens(text: &str) -> Vec<Token> {
    let chars: Vec<char> = text.trim().chars().collect();
    let mut found = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let after_name = i > 0 && (chars[i - 1].is_alphanumeric() || "_.".contains(chars[i - 1]));
        let signed = "+-".contains(chars[i]) && chars.get(i + 1).is_some_and(char::is_ascii_digit);
        if !after_name && (chars[i].is_ascii_digit() || signed) {
            let end = number_end(&chars, i);
            let number: String = chars[i..end].iter().collect();
            found.push(Token::Number(number.parse().expect("a number")));
            i = end;
        } else if chars[i].is_whitespace() {
            if found.last() != Some(&Token::Text(' ')) {
                found.push(Token::Text(' '));
            }
            i += 1;
        } else {
            found.push(Token::Text(chars[i]));
            i += 1;
        }
    }
    found
}

/// Where the number starting at `start` of `chars` ends.
fn number_end(chars: &[char], start: usize) -> usize {
    let digits = |mut i: usize| {
        while chars.get(i).is_some_and(char::is_ascii_digit) {
            i += 1;
        }
        i
    };
    let mut end = digits(start + 1);
    if chars.get(end) == Some(&'.') && chars.get(end + 1).is_some_and(char::is_ascii_digit) {
        end = digits(end + 1);
    }
    if chars.get(end).is_some_and(|c| "eE".contains(*c)) {
        let sign = usize::from(chars.get(end + 1).is_some_and(|c| "+-".contains(*c)));
        if chars.get(end + 1 + sign).is_some_and(char::is_ascii_digit) {
            end = digits(end + 1 + sign);
        }
    }
    end
}

/// The numbers of `line`, in order.
pub fn numbers(line: &str) -> Vec<f64> {
    (tokens(line).into_iter())
        .filter_map(|token| match token {
            Token::Number(value) => Some(value),
            Token::Text(_) => None,
        })
        .collect()
}
