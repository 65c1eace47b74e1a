use quote::quote;

use super::*;
use crate::fixtures::SNAKEBOARD;

/// Prints an expression with every operation parenthesized: `(a*(b^c))`.
fn parenthesized(expr: &Expr) -> String {
    match expr {
        Expr::Number { literal, .. } => literal.clone(),
        Expr::Name(name) => name.to_string(),
        Expr::Call {
            function,
            arguments,
            keywords,
            ..
        } => {
            let keywords = (keywords.iter()).map(|k| format!("{} = {}", k.name, printed(&k.value)));
            let arguments: Vec<String> = arguments.iter().map(printed).chain(keywords).collect();
            format!("{function}({})", arguments.join(", "))
        }
        Expr::Field { base, field } => format!("{}.{field}", parenthesized(base)),
        Expr::Negate { operand, .. } => format!("(-{})", parenthesized(operand)),
        Expr::Binary {
            operator,
            left,
            right,
            ..
        } => format!(
            "({}{operator}{})",
            parenthesized(left),
            parenthesized(right)
        ),
    }
}

/// Prints a value: lists as `[item, name = item]`, expressions parenthesized.
fn printed(value: &Value) -> String {
    match value {
        Value::Expr(expr) => parenthesized(expr),
        Value::List(list) => {
            let items: Vec<String> = list
                .items
                .iter()
                .map(|item| match item {
                    Item::Named { name, value } => format!("{name} = {}", printed(value)),
                    Item::Plain(value) => printed(value),
                })
                .collect();
            format!("[{}]", items.join(", "))
        }
    }
}

fn parsed(source: &str) -> ModelSyntax {
    match parse_str(source) {
        Ok(model) => model,
        Err(errors) => panic!(
            "{source:?} should parse, got:\n{}",
            errors.render("m.model")
        ),
    }
}

/// The single section value of `struct M { value: SOURCE }`, printed.
fn value_of(source: &str) -> String {
    let model = parsed(&format!("struct M {{ value: {source} }}"));
    printed(&model.sections[0].value)
}

/// The rendered errors for a model text that must fail.
fn errors(source: &str) -> String {
    match parse_str(source) {
        Ok(model) => panic!("{source:?} should fail, parsed {model:?}"),
        Err(errors) => errors.render("m.model"),
    }
}

fn section<'a>(model: &'a ModelSyntax, key: &str) -> &'a Value {
    let found = model.sections.iter().find(|section| section.key == key);
    match found {
        Some(section) => &section.value,
        None => panic!("no section `{key}`"),
    }
}

fn list(value: &Value) -> &List {
    value
        .as_list()
        .unwrap_or_else(|| panic!("not a list: {value:?}"))
}

#[test]
fn snakeboard_has_its_header_and_nine_sections() {
    let model = parsed(SNAKEBOARD);
    assert_eq!(
        model.docs,
        [" Snakeboard with J = Jt + m r^2 (Duindam & Stramigioli 2004)."]
    );
    assert!(model.attributes.is_empty());
    assert_eq!(model.visibility.to_string(), "pub");
    assert_eq!(model.name, "Snakeboard");
    let keys: Vec<String> = model.sections.iter().map(|s| s.key.to_string()).collect();
    assert_eq!(
        keys,
        [
            "coordinates",
            "parameters",
            "define",
            "kinetic_energy",
            "potential_energy",
            "constraints",
            "inputs",
            "momentum_basis",
            "symmetry"
        ]
    );
}

#[test]
fn snakeboard_lists_have_the_declared_items() {
    let model = parsed(SNAKEBOARD);
    assert_eq!(
        printed(section(&model, "coordinates")),
        "[x, y, theta, psi, phi]"
    );
    assert_eq!(
        printed(section(&model, "parameters")),
        "[m = 1.0, r = 0.5, jt = 0.3, jw = 0.05]"
    );
    assert_eq!(printed(section(&model, "define")), "[j = (jt+(m*(r^2)))]");
    assert_eq!(
        printed(section(&model, "inputs")),
        "[u_torso = psi, u_wheels = phi]"
    );
    let constraints = list(section(&model, "constraints"));
    let names: Vec<String> = constraints
        .items
        .iter()
        .filter_map(|item| item.name().map(ToString::to_string))
        .collect();
    assert_eq!(names, ["front", "back"]);
}

#[test]
fn snakeboard_momentum_basis_rows_are_named_lists_of_five() {
    let model = parsed(SNAKEBOARD);
    let basis = list(section(&model, "momentum_basis"));
    assert_eq!(basis.items.len(), 3);
    for (item, expected) in basis.items.iter().zip(["group", "torso", "wheels"]) {
        let Item::Named { name, value } = item else {
            panic!("row should be named: {item:?}");
        };
        assert_eq!(name, expected);
        let row = list(value);
        assert_eq!(row.items.len(), 5);
        assert!(
            row.items
                .iter()
                .all(|entry| matches!(entry, Item::Plain(Value::Expr(_))))
        );
    }
    assert_eq!(
        printed(basis.items[0].value()),
        "[(cos(phi)*cos(theta)), (cos(phi)*sin(theta)), (r*sin(phi)), 0, 0]"
    );
}

#[test]
fn snakeboard_expressions_keep_their_structure() {
    let model = parsed(SNAKEBOARD);
    assert_eq!(printed(section(&model, "potential_energy")), "0");
    assert_eq!(printed(section(&model, "symmetry")), "se2(x, y, theta)");
    assert_eq!(
        printed(section(&model, "kinetic_energy")),
        "((((((m/2)*((dot(x)^2)+(dot(y)^2)))+((j/2)*(dot(theta)^2)))\
         +((jt*dot(theta))*dot(psi)))+((jt/2)*(dot(psi)^2)))+((jw/2)*(dot(phi)^2)))"
    );
    let front = list(section(&model, "constraints")).items[0].value();
    assert_eq!(
        printed(front),
        "((((-sin((theta+phi)))*dot(x))+(cos((theta+phi))*dot(y)))+((r*cos(phi))*dot(theta)))"
    );
}

#[test]
fn operators_follow_precedence_and_associativity() {
    for (source, expected) in [
        ("a*b^c^d", "(a*(b^(c^d)))"),
        ("a - b - c", "((a-b)-c)"),
        ("a/b*c", "((a/b)*c)"),
        ("a + b*c", "(a+(b*c))"),
        ("a*b + c", "((a*b)+c)"),
        ("-x^2", "(-(x^2))"),
        ("x^-1", "(x^(-1))"),
        ("2^-3^2", "(2^(-(3^2)))"),
        ("2*-x", "(2*(-x))"),
        ("a - -b", "(a-(-b))"),
        ("--x", "(-(-x))"),
        ("-x*y", "((-x)*y)"),
        ("2^-3*4", "((2^(-3))*4)"),
        ("(a + b)*c", "((a+b)*c)"),
        ("((x))", "x"),
        ("x^(1/2)", "(x^(1/2))"),
        ("a^b*c", "((a^b)*c)"),
    ] {
        assert_eq!(value_of(source), expected, "{source}");
    }
}

#[test]
fn numbers_keep_their_text() {
    for (source, expected) in [
        ("2", "2"),
        ("0.5", "0.5"),
        ("1e-3", "1e-3"),
        ("1.5E2", "1.5E2"),
        ("1_000", "1000"),
        ("-0.05", "(-0.05)"),
    ] {
        assert_eq!(value_of(source), expected, "{source}");
    }
}

#[test]
fn calls_names_and_nested_lists_parse() {
    assert_eq!(value_of("f()"), "f()");
    assert_eq!(value_of("se2(x, y, theta,)"), "se2(x, y, theta)");
    assert_eq!(value_of("sqrt(x^2 + y^2)"), "sqrt(((x^2)+(y^2)))");
    assert_eq!(value_of("dot"), "dot");
    assert_eq!(value_of("[[m, 0], [0, m],]"), "[[m, 0], [0, m]]");
    assert_eq!(value_of("[]"), "[]");
    assert_eq!(value_of("[u = [1, 0], v = q]"), "[u = [1, 0], v = q]");
    assert_eq!(
        value_of("translation(x) * rotation(theta)"),
        "(translation(x)*rotation(theta))"
    );
}

#[test]
fn spans_point_at_the_right_tokens() {
    let model = parsed("struct M {\n    e: a + sin(b)*-c,\n    l: [1, 2],\n}");
    let Value::Expr(Expr::Binary { left, right, .. }) = &model.sections[0].value else {
        panic!("expected a sum");
    };
    let column = |span: proc_macro2::Span| (span.start().line, span.start().column + 1);
    assert_eq!(column(model.sections[0].value.span()), (2, 8));
    assert_eq!(column(left.span()), (2, 8));
    let sum = model.sections[0].value.as_expr();
    assert_eq!(sum.map(|sum| column(sum.span())), Some((2, 10)));
    let Expr::Binary {
        left: call,
        right: negation,
        ..
    } = right.as_ref()
    else {
        panic!("expected a product");
    };
    assert_eq!(column(right.span()), (2, 18));
    assert_eq!(column(right.first_span()), (2, 12));
    assert_eq!(column(call.span()), (2, 12));
    let Expr::Call {
        span: parentheses, ..
    } = call.as_ref()
    else {
        panic!("expected a call");
    };
    assert_eq!(column(*parentheses), (2, 15));
    assert_eq!(column(negation.span()), (2, 19));
    assert_eq!(column(model.sections[1].value.span()), (3, 8));
    assert_eq!(column(model.name.span()), (1, 8));
}

#[test]
fn doc_comments_and_attributes_are_captured() {
    let model = parsed(
        "/// First line.\n///\n/// Third \"line\".\n#[doc = \"escaped \\\" \\\\ end\"]\n\
         /** block */\n#[deny_holonomic]\n#[chaplygin(report = \"x\")]\nstruct M {}",
    );
    assert_eq!(
        model.docs,
        [
            " First line.",
            "",
            " Third \"line\".",
            "escaped \" \\ end",
            " block "
        ]
    );
    let attributes: Vec<String> = model
        .attributes
        .iter()
        .map(|attribute| format!("{} {}", attribute.name, attribute.tokens))
        .collect();
    assert_eq!(
        attributes,
        ["deny_holonomic ", "chaplygin (report = \"x\")"]
    );
    assert!(model.sections.is_empty());
}

#[test]
fn visibility_is_kept_as_written() {
    for (source, expected) in [
        ("struct M {}", ""),
        ("pub struct M {}", "pub"),
        ("pub(crate) struct M {}", "pub (crate)"),
        ("pub(super) struct M {}", "pub (super)"),
        ("pub(in crate::a) struct M {}", "pub (in crate :: a)"),
    ] {
        assert_eq!(parsed(source).visibility.to_string(), expected, "{source}");
    }
}

#[test]
fn tokens_from_quote_parse() {
    let tokens = quote! {
        /// Quoted.
        pub struct S { coordinates: [x] }
    };
    let model = match parse(tokens) {
        Ok(model) => model,
        Err(errors) => panic!("{errors}"),
    };
    assert_eq!(model.docs, [" Quoted."]);
    assert_eq!(model.name, "S");
    assert_eq!(model.sections.len(), 1);
    assert_eq!(printed(&model.sections[0].value), "[x]");
}

#[test]
fn interpolated_negative_literals_are_negations() {
    let value = proc_macro2::Literal::f64_unsuffixed(-2.5);
    let model = parse(quote! { struct S { e: x^#value } });
    let printed = model.map(|model| printed(&model.sections[0].value));
    assert_eq!(printed.ok().as_deref(), Some("(x^(-2.5))"));
}

#[test]
fn missing_colon_names_the_section() {
    assert_eq!(
        errors("struct M {\n    kinetic_energy = 1,\n}"),
        "m.model:2:20: error: expected `:` after the section name `kinetic_energy`, found `=`\n"
    );
}

#[test]
fn unknown_tokens_are_reported_where_they_are() {
    assert_eq!(
        errors("struct M {\n    potential_energy: 0;\n}"),
        "m.model:2:24: error: expected one of: `+`, `-`, `*`, `/`, `^`, `,`, `}`, \
         found `;`\n"
    );
    assert_eq!(
        errors("struct M {\n    e: m @ x,\n}"),
        "m.model:2:10: error: expected one of: `+`, `-`, `*`, `/`, `^`, `,`, `}`, \
         found `@`\n"
    );
    assert_eq!(
        errors("struct M { e: @x }"),
        "m.model:1:15: error: expected an operand (a number, a name, a call like `sin(x)`, \
         or `( ... )`), found `@`\n"
    );
    assert_eq!(
        errors("struct M { e: a b }"),
        "m.model:1:17: error: expected one of: `+`, `-`, `*`, `/`, `^`, `,`, `}`, \
         found `b`\n"
    );
}

#[test]
fn unbalanced_delimiters_are_lex_errors() {
    assert_eq!(
        errors("struct M {\n    coordinates: [x, y,\n}"),
        "m.model:3:1: error: unmatched closing delimiter `}`: \
         it does not close the innermost open delimiter\n"
    );
    assert_eq!(
        errors("struct M {\n    e: sin(x"),
        "m.model:2:11: error: unclosed delimiter `(`: it has no matching closing delimiter\n"
    );
    assert_eq!(
        errors("struct M {}\n)"),
        "m.model:2:1: error: unmatched closing delimiter `)`: \
         it does not close the innermost open delimiter\n"
    );
    assert!(errors("struct M { e: \"open }").starts_with("m.model:1:15: error: cannot read"));
}

#[test]
fn suffixed_and_string_literals_are_rejected() {
    assert_eq!(
        errors("struct M {\n    parameters: [m = 1.0f64],\n}"),
        "m.model:2:22: error: the number `1.0f64` has a type suffix `f64`: \
         numbers in a model are untyped, write `1.0`\n"
    );
    assert_eq!(
        errors("struct M { e: 2u8 }"),
        "m.model:1:15: error: the number `2u8` has a type suffix `u8`: \
         numbers in a model are untyped, write `2`\n"
    );
    assert_eq!(
        errors("struct M { e: \"one\" }"),
        "m.model:1:15: error: expected a number, found the string or character literal \
         `\"one\"`: models only contain numbers, names and operators\n"
    );
    assert!(errors("struct M { e: 'c' }").contains("1:15: error: expected a number"));
    assert!(errors("struct M { e: 0x10 }").contains("1:15: error: expected a decimal number"));
}

#[test]
fn tokens_after_the_closing_brace_are_rejected() {
    assert_eq!(
        errors("struct M {\n    e: 1,\n} extra"),
        "m.model:3:3: error: unexpected tokens after the model's closing brace: found `extra`\n"
    );
    assert_eq!(
        errors("struct M { e: 1; } ;"),
        "m.model:1:16: error: expected one of: `+`, `-`, `*`, `/`, `^`, `,`, `}`, \
         found `;`\n\
         m.model:1:20: error: unexpected tokens after the model's closing brace: found `;`\n"
    );
}

#[test]
fn missing_header_pieces_are_reported() {
    let expected_struct =
        "m.model:1:1: error: expected `struct Name { ... }`, found the end of the input\n";
    assert_eq!(errors(""), expected_struct);
    assert_eq!(errors("  // only a comment\n"), expected_struct);
    assert_eq!(
        errors("pub struct"),
        "m.model:1:5: error: expected the model's name after `struct`, found the end of the input\n"
    );
    assert_eq!(
        errors("struct { }"),
        "m.model:1:8: error: expected the model's name after `struct`, found `{`\n"
    );
    assert_eq!(
        errors("struct M;"),
        "m.model:1:9: error: expected `{` and the model's sections after `struct M`, found `;`\n"
    );
    assert_eq!(
        errors("model M {}"),
        "m.model:1:1: error: expected `struct Name { ... }`, found `model`\n"
    );
    assert_eq!(
        errors("# struct M {}"),
        "m.model:1:3: error: expected `[` after `#` to start an attribute, found `struct`\n"
    );
}

#[test]
fn errors_in_different_sections_are_all_reported() {
    assert_eq!(
        errors("struct M {\n    coordinates: [x y],\n    potential_energy = 0,\n}"),
        "m.model:2:21: error: expected one of: `+`, `-`, `*`, `/`, `^`, `,`, `]`, \
         found `y`\n\
         m.model:3:22: error: expected `:` after the section name `potential_energy`, found `=`\n"
    );
}

#[test]
fn errors_in_different_items_and_arguments_are_all_reported() {
    let lines = error_lines(
        "struct M { l: [a +, b, 1f32], e: f(*, 2u8) }",
        &[
            "m.model:1:19: error: expected an operand",
            "m.model:1:24: error: the number `1f32`",
            "m.model:1:36: error: expected an operand",
            "m.model:1:39: error: the number `2u8`",
        ],
    );
    assert!(lines[2].ends_with("found `*` (powers are written `x^2`, not `x**2`)"));
}

/// The rendered error lines of a failing model text, checked to start with
/// `prefixes`, one line each.
fn error_lines(source: &str, prefixes: &[&str]) -> Vec<String> {
    let rendered = errors(source);
    let lines: Vec<String> = rendered.lines().map(str::to_owned).collect();
    assert_eq!(lines.len(), prefixes.len(), "{rendered}");
    for (line, prefix) in lines.iter().zip(prefixes) {
        assert!(
            line.starts_with(prefix),
            "{line} should start with {prefix}"
        );
    }
    lines
}

#[test]
fn empty_items_sections_and_arguments_are_reported_at_their_comma() {
    assert_eq!(
        errors("struct M { l: [a, , b] }"),
        "m.model:1:19: error: empty list item: expected a value before this `,`\n"
    );
    assert_eq!(
        errors("struct M { e: 1,, }"),
        "m.model:1:17: error: empty section: expected `name: value` before this `,`\n"
    );
    assert_eq!(
        errors("struct M { e: f(,x) }"),
        "m.model:1:17: error: empty argument: expected an expression before this `,`\n"
    );
    assert_eq!(
        errors("struct M { e: , }"),
        "m.model:1:15: error: expected a value after `e:`, found `,`\n"
    );
    assert_eq!(
        errors("struct M { l: [m = ] }"),
        "m.model:1:20: error: expected a value after `m =`, found `]`\n"
    );
    assert_eq!(
        errors("struct M { e: () }"),
        "m.model:1:15: error: empty parentheses: expected an expression inside `( )`\n"
    );
}

#[test]
fn misplaced_lists_and_sections_are_reported() {
    assert_eq!(
        errors("struct M { l: [1] * 2 }"),
        "m.model:1:19: error: expected `,` after the list (a list `[...]` is a whole value), \
         found `*`\n"
    );
    assert_eq!(
        errors("struct M { e: 2 * [1] }"),
        "m.model:1:19: error: a list `[...]` cannot be part of an expression; \
         lists are whole values such as `[a, b]`, or call arguments\n"
    );
    assert_eq!(
        errors("struct M { 1: x }"),
        "m.model:1:12: error: expected a section name such as `coordinates`, found `1`\n"
    );
    assert_eq!(
        errors("struct M { e: (a, b) }"),
        "m.model:1:17: error: expected one of: `+`, `-`, `*`, `/`, `^`, `)`, found `,`\n"
    );
}

#[test]
fn attributes_inside_the_body_are_reported() {
    assert_eq!(
        errors("struct M {\n    /// The mass.\n    e: 1,\n}"),
        "m.model:2:5: error: doc comments and attributes are only allowed before `struct`; \
         use `//` comments inside the model\n"
    );
    assert!(
        errors("//! Inner.\nstruct M {}")
            .starts_with("m.model:1:1: error: inner attributes and `//!` comments")
    );
}

#[test]
fn hostile_nesting_is_an_error_not_a_crash() {
    let parentheses = format!("struct M {{ e: {}x{} }}", "(".repeat(500), ")".repeat(500));
    assert!(errors(&parentheses).contains("error: nested too deeply"));
    let minus = format!("struct M {{ e: {}x }}", "-".repeat(500));
    assert!(errors(&minus).contains("error: nested too deeply"));
    let lists = format!("struct M {{ e: {}x{} }}", "[".repeat(500), "]".repeat(500));
    assert!(errors(&lists).contains("error: nested too deeply"));
    let long_sum = format!("struct M {{ e: x{} }}", "+x".repeat(MAX_EXPRESSION_DEPTH));
    assert!(errors(&long_sum).contains("error: expression too deep"));
    let fitting_sum = format!(
        "struct M {{ e: x{} }}",
        "+x".repeat(MAX_EXPRESSION_DEPTH - 1)
    );
    assert!(parse_str(&fitting_sum).is_ok());
}

#[test]
fn no_prefix_or_mutation_of_a_model_panics() {
    let characters: Vec<char> = SNAKEBOARD.chars().collect();
    for end in 0..characters.len() {
        let prefix: String = characters[..end].iter().collect();
        let _ = parse_str(&prefix);
        for junk in [";", "@", "(", "]", "\"", "1f32", ",", "=", "^", "#", "-"] {
            let mut mutated = prefix.clone();
            mutated.push_str(junk);
            mutated.extend(&characters[end..]);
            let _ = parse_str(&mutated);
        }
    }
}

#[test]
fn compile_errors_are_spanned_invocations() {
    let errors = parse(quote! { struct S { e: 1f32, f: [,] } }).err();
    let text = errors.map(|errors| errors.to_compile_errors().to_string());
    let text = text.unwrap_or_default();
    assert_eq!(
        text.matches(":: core :: compile_error !").count(),
        2,
        "{text}"
    );
}

#[test]
fn field_selection_binds_tighter_than_every_operator() {
    assert_eq!(value_of("origin + x*ground.x"), "(origin+(x*ground.x))");
    assert_eq!(value_of("-r*lean.z^2"), "((-r)*(lean.z^2))");
    assert_eq!(value_of("cross(a, b).y"), "cross(a, b).y");
    assert_eq!(value_of("(c - o).x.y"), "(c-o).x.y");
}

#[test]
fn lists_are_call_arguments() {
    assert_eq!(
        value_of("no_slip(wheel, contact, [ground.x, ground.y])"),
        "no_slip(wheel, contact, [ground.x, ground.y])"
    );
    assert_eq!(
        value_of("body(b, c, m, [[1, 0, 0], [0, 2, 0], [0, 0, 3]])"),
        "body(b, c, m, [[1, 0, 0], [0, 2, 0], [0, 0, 3]])"
    );
}

#[test]
fn calls_take_keyword_arguments_after_their_positional_ones() {
    assert_eq!(
        value_of("box(center = [x, y, 0.05], heading = theta, size = [2*l, 0.3, 0.02])"),
        "box(center = [x, y, 0.05], heading = theta, size = [(2*l), 0.3, 0.02])"
    );
    assert_eq!(
        value_of("f(a, radius = -r^2, b)"),
        "f(a, b, radius = (-(r^2)))"
    );
    let text = errors("struct M { value: f(radius = ) }");
    assert!(
        text.contains("expected a value after `radius =`, found `)`"),
        "{text}"
    );
}

#[test]
fn a_field_needs_a_name_and_a_list_argument_stands_alone() {
    let text = errors("struct M { value: ground. }");
    assert!(text.contains("expected a field name after `.`"), "{text}");
    let text = errors("struct M { value: f([a] + 1) }");
    assert!(
        text.contains("expected `,` after the list (a list `[...]` is a whole value), found `+`"),
        "{text}"
    );
    let text = errors("struct M { value: 1 + [a] }");
    assert!(text.contains("cannot be part of an expression"), "{text}");
}

#[test]
fn every_error_of_a_model_is_reported_together() {
    error_lines(
        "//! Inner.\nstruct M {\n    a: [x y],\n    b: f(1, 2u8),\n    c = 1,\n} extra",
        &[
            "m.model:1:1: error: inner attributes",
            "m.model:3:11: error: expected one of",
            "m.model:4:13: error: the number `2u8`",
            "m.model:5:7: error: expected `:` after the section name `c`",
            "m.model:6:3: error: unexpected tokens after",
        ],
    );
}

#[test]
fn expected_one_of_names_what_may_follow_an_operand() {
    let operators = "expected one of: `+`, `-`, `*`, `/`, `^`";
    assert_eq!(
        errors("struct M { l: [a b] }"),
        format!("m.model:1:18: error: {operators}, `,`, `]`, found `b`\n")
    );
    assert_eq!(
        errors("struct M { e: f(a b) }"),
        format!("m.model:1:19: error: {operators}, `,`, `)`, found `b`\n")
    );
    assert_eq!(
        errors("struct M { e: (a b) }"),
        format!("m.model:1:18: error: {operators}, `)`, found `b`\n")
    );
    assert_eq!(
        errors("struct M { e: a.x y }"),
        format!("m.model:1:19: error: {operators}, `,`, `}}`, found `y`\n")
    );
}

#[test]
fn the_syntax_tree_types_parse_with_syn() -> syn::Result<()> {
    assert_eq!(parenthesized(&syn::parse_str::<Expr>("-x^2")?), "(-(x^2))");
    assert_eq!(
        printed(&syn::parse_str::<Value>("[a, m = 1]")?),
        "[a, m = 1]"
    );
    let item = syn::parse_str::<Item>("m = 2*g")?;
    assert_eq!(item.name().map(ToString::to_string).as_deref(), Some("m"));
    assert_eq!(
        printed(syn::parse_str::<List>("[[1], x]")?.items[0].value()),
        "[1]"
    );
    let section = syn::parse_str::<Section>("coordinates: [x, y]")?;
    assert_eq!(
        (section.key.to_string(), printed(&section.value)),
        ("coordinates".to_owned(), "[x, y]".to_owned())
    );
    let attribute = syn::parse_str::<Attribute>("chaplygin(report)")?;
    assert_eq!(attribute.tokens.to_string(), "(report)");
    let model = syn::parse_str::<ModelSyntax>("/// M.\nstruct M { e: 1 }")?;
    assert_eq!(
        (model.docs, model.sections.len()),
        (vec![" M.".to_owned()], 1)
    );
    let error = syn::parse_str::<Expr>("a b")
        .err()
        .map(|error| error.to_string());
    assert_eq!(
        error.as_deref(),
        Some("expected one of: `+`, `-`, `*`, `/`, `^`, found `b`")
    );
    Ok(())
}

#[test]
fn nesting_too_deep_for_syn_to_buffer_is_rejected_first() {
    let depth = 100_000;
    let parentheses = format!(
        "struct M {{ e: {}x{} }}",
        "(".repeat(depth),
        ")".repeat(depth)
    );
    assert_eq!(
        errors(&parentheses),
        format!(
            "m.model:1:{}: error: nested too deeply (more than 200 levels of parentheses, \
             lists, calls or operators); split the expression with `define`\n",
            // the body's braces are the first level: the 200th parenthesis,
            // at column 15 + 199, is the 201st
            15 + 199
        )
    );
}

#[test]
fn interpolated_groups_are_operands() {
    let group = proc_macro2::Group::new(proc_macro2::Delimiter::None, quote!(a + b));
    let model = parse(quote! { struct S { e: x * #group } });
    let printed = model.map(|model| printed(&model.sections[0].value));
    assert_eq!(printed.ok().as_deref(), Some("(x*(a+b))"));
}

#[test]
fn a_doc_attribute_needs_a_string() {
    assert_eq!(
        errors("#[doc = 1]\nstruct M {}"),
        "m.model:1:2: error: expected a string literal in `#[doc = \"...\"]`\n"
    );
}
