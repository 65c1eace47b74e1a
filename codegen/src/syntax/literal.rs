//! Numbers in a model: untyped decimal literals only.

/// Checks that `text` (a literal token's text, without a leading `-`) is an
/// untyped decimal number and returns it without `_` separators.
///
/// The error is the complete message for the user.
pub(super) fn decimal_number(text: &str) -> Result<String, String> {
    if !text.starts_with(|character: char| character.is_ascii_digit()) {
        return Err(format!(
            "expected a number, found the string or character literal `{text}`: \
             models only contain numbers, names and operators"
        ));
    }
    if ["0x", "0o", "0b"]
        .iter()
        .any(|prefix| text.starts_with(prefix))
    {
        return Err(format!(
            "expected a decimal number, found `{text}`: write numbers in base 10"
        ));
    }
    let number_length = decimal_prefix_length(text);
    let (number, suffix) = text.split_at(number_length);
    if suffix.is_empty() {
        Ok(number.replace('_', ""))
    } else {
        Err(format!(
            "the number `{text}` has a type suffix `{suffix}`: numbers in a model are untyped, \
             write `{number}`"
        ))
    }
}

/// The length of the longest prefix of the form
/// `digits [. digits] [(e|E) [+|-] digits]`, where digits may contain `_`.
fn decimal_prefix_length(text: &str) -> usize {
    let bytes = text.as_bytes();
    let mut length = digits_length(bytes);
    if bytes.get(length) == Some(&b'.') {
        length += 1 + digits_length(&bytes[length + 1..]);
    }
    length + exponent_length(&bytes[length..])
}

/// The length of an exponent `(e|E) [+|-] digits` at the start of `bytes`,
/// or 0 when there is none (a lone `e` is a suffix, not an exponent).
fn exponent_length(bytes: &[u8]) -> usize {
    if !matches!(bytes.first(), Some(b'e' | b'E')) {
        return 0;
    }
    let sign = usize::from(matches!(bytes.get(1), Some(b'+' | b'-')));
    let digits = digits_length(&bytes[1 + sign..]);
    let has_digit = bytes[1 + sign..1 + sign + digits]
        .iter()
        .any(u8::is_ascii_digit);
    if has_digit { 1 + sign + digits } else { 0 }
}

/// The length of the run of ASCII digits and `_` at the start of `bytes`.
fn digits_length(bytes: &[u8]) -> usize {
    bytes
        .iter()
        .take_while(|byte| byte.is_ascii_digit() || **byte == b'_')
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_numbers_are_accepted_and_normalized() {
        for (text, expected) in [
            ("2", "2"),
            ("0.05", "0.05"),
            ("1e-3", "1e-3"),
            ("1.5E2", "1.5E2"),
            ("1.", "1."),
            ("1_000.5", "1000.5"),
            ("2E+7", "2E+7"),
        ] {
            assert_eq!(decimal_number(text).as_deref(), Ok(expected), "{text}");
            assert!(expected.parse::<f64>().is_ok(), "{expected}");
        }
    }

    #[test]
    fn suffixes_radixes_and_strings_are_rejected() {
        let message = |text| decimal_number(text).err().unwrap_or_default();
        assert!(message("1.0f64").contains("type suffix `f64`"));
        assert!(message("2u8").contains("write `2`"));
        assert!(message("1e3f32").contains("type suffix `f32`"));
        assert!(message("1e").contains("type suffix `e`"));
        assert!(message("0x1F").contains("base 10"));
        assert!(message("\"abc\"").contains("string or character literal"));
        assert!(message("'c'").contains("string or character literal"));
    }
}
