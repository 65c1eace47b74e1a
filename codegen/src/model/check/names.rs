//! Names: coordinates, parameters and definitions, each declared once.

use super::*;

impl Checker {
    // ----- names ---------------------------------------------------------

    /// A name is declared once, among coordinates, parameters and definitions,
    /// and is not a function name.
    pub(super) fn rule_fresh_name(&mut self, name: &str, span: Span, kind: &'static str) -> bool {
        if FUNCTIONS.contains(&name) || name == "dot" {
            self.diagnostics.error(
                span,
                format!("`{name}` is a function of the model language and cannot name a {kind}"),
            );
            return false;
        }
        if let Some(&(first, _)) = self.declared.get(name) {
            let message = if kind == "parameter" && first == "coordinate" {
                format!("`{name}` is a coordinate and cannot also be used as a parameter")
            } else if first == kind {
                format!("`{name}` is declared twice as a {kind}")
            } else {
                format!("`{name}` is declared twice: first as a {first}, again as a {kind}")
            };
            self.diagnostics.error(span, message);
            return false;
        }
        self.declared.insert(name.to_string(), (kind, span));
        true
    }

    /// Names of constraints, inputs and momentum-basis rows are unique in their section.
    pub(super) fn rule_unique_in_section(
        &mut self,
        names: &[Declared],
        name: &str,
        span: Span,
    ) -> bool {
        let unique = !names.iter().any(|d| d.name == name);
        if !unique {
            self.diagnostics
                .error(span, format!("`{name}` is declared twice in this section"));
        }
        unique
    }

    /// A list item is `name = value`.
    pub(super) fn named_item<'a>(
        &mut self,
        item: &'a Item,
        what: &str,
    ) -> Option<(Declared, &'a Value)> {
        match item {
            Item::Named { name, value } => Some((
                Declared {
                    name: name.to_string(),
                    span: name.span(),
                },
                value,
            )),
            Item::Plain(value) => {
                self.diagnostics
                    .error(value.span(), format!("expected `name = ...` for {what}"));
                None
            }
        }
    }

    pub(super) fn coordinates(&mut self, section: Option<&&Section>) -> Vec<Variable> {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return Vec::new();
        };
        if list.items.is_empty() {
            self.diagnostics
                .error(list.span, "a model needs at least one coordinate");
        }
        let mut coordinates = Vec::new();
        for item in &list.items {
            let Item::Plain(Value::Expr(Expr::Name(ident))) = item else {
                self.diagnostics.error(
                    item.span(),
                    "a coordinate is declared by its name alone, e.g. `theta`",
                );
                continue;
            };
            let name = ident.to_string();
            if !self.rule_fresh_name(&name, ident.span(), "coordinate") {
                continue;
            }
            // The nodes of the symbols are made in declaration order, so that
            // printed products list their factors in that order however the
            // derivations proceed.
            let symbol = self.store.declare(&name, SymbolKind::Coordinate);
            let velocity = self.store.velocity_of(symbol);
            self.store.symbol(symbol);
            self.store.symbol(velocity);
            self.scope.bind(&name, Binding::Coordinate(symbol));
            coordinates.push(Variable {
                declared: Declared {
                    name,
                    span: ident.span(),
                },
                symbol,
            });
        }
        coordinates
    }

    pub(super) fn parameters(&mut self, section: Option<&&Section>) -> Vec<Parameter> {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return Vec::new();
        };
        let mut parameters = Vec::new();
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a parameter and its default")
            else {
                continue;
            };
            let default = self.rule_numeric_default(value);
            let field_ok = self.rule_field_name(&declared);
            if !self.rule_fresh_name(&declared.name, declared.span, "parameter") || !field_ok {
                continue;
            }
            // Declared even when its default is wrong, so its uses are not reported too.
            let symbol = self.store.declare(&declared.name, SymbolKind::Parameter);
            self.store.symbol(symbol);
            self.scope.bind(&declared.name, Binding::Parameter(symbol));
            let Some(default) = default else { continue };
            parameters.push(Parameter {
                variable: Variable { declared, symbol },
                default,
            });
        }
        parameters
    }

    /// A parameter's default is a number literal, possibly negated.
    pub(super) fn rule_numeric_default(&mut self, value: &Value) -> Option<Rational> {
        let parsed = match value {
            Value::Expr(Expr::Number { literal, .. }) => Rational::from_decimal(literal),
            Value::Expr(Expr::Negate { operand, .. }) => match operand.as_ref() {
                Expr::Number { literal, .. } => Rational::from_decimal(literal).map(|r| r.neg()),
                _ => None,
            },
            _ => None,
        };
        if parsed.is_none() {
            let coordinate = match value {
                Value::Expr(Expr::Name(name)) => self
                    .declared
                    .get(&name.to_string())
                    .is_some_and(|(kind, _)| *kind == "coordinate"),
                _ => false,
            };
            let message = if coordinate {
                "a parameter's default must be a number, and this is a coordinate (parameters are \
                 constants), e.g. `m = 1.0` or `g = -9.81`"
            } else {
                "a parameter's default must be a number, e.g. `m = 1.0` or `g = -9.81`"
            };
            self.diagnostics.error(value.span(), message);
        }
        parsed
    }

    /// A parameter name can be a struct field (not a Rust keyword).
    pub(super) fn rule_field_name(&mut self, declared: &Declared) -> bool {
        let ok = !KEYWORDS.contains(&declared.name.as_str());
        if !ok {
            self.diagnostics.error(
                declared.span,
                format!(
                    "`{}` is a Rust keyword and cannot name a parameter (parameters become \
                     struct fields)",
                    declared.name
                ),
            );
        }
        ok
    }

    pub(super) fn definitions(&mut self, section: Option<&&Section>) {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return;
        };
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a definition") else {
                continue;
            };
            let Some(expr) = self.item_expression(value) else {
                continue;
            };
            let lowered = self.lower(expr);
            if !self.rule_fresh_name(&declared.name, declared.span, "definition") {
                continue;
            }
            // A definition that failed is still declared, so its uses are not reported too.
            let id = lowered.unwrap_or_else(|| {
                let placeholder = self.store.declare(&declared.name, SymbolKind::Auxiliary);
                self.store.symbol(placeholder)
            });
            self.scope.bind(&declared.name, Binding::Definition(id));
        }
    }

    pub(super) fn item_expression<'a>(&mut self, value: &'a Value) -> Option<&'a Expr> {
        let expr = value.as_expr();
        if expr.is_none() {
            self.diagnostics
                .error(value.span(), "expected an expression, found a list");
        }
        expr
    }
}
