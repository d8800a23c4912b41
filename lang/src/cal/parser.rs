//! The calcomp grammar as Radiance's recursive descent implies it (calexpr.c `getE1`
//! .. `getE5`, caldefn.c `egetdefn`, `egetchan`):
//!
//! ```text
//! stmt : ID ['(' ID {',' ID} ')'] ('='|':') E1  |  '$' INT '=' E1
//! E1   : E2 {('+'|'-') E2}        left-associative
//! E2   : E3 {('*'|'/') E3}        left-associative
//! E3   : E4 ['^' E3]              right-associative
//! E4   : ['+'|'-'] E5             one sign, binding tighter than '^': -2^2 is 4
//! E5   : '(' E1 ')' | '$' INT | ID | ID '(' E1 {',' E1} ')' | NUM
//! ```
//!
//! Statements are separated by `;`, which can appear nowhere else, so the token list is
//! cut at each `;` and every statement parsed on its own: a bad statement is reported
//! and the next one still parsed (Radiance stops at the first error).

use super::lexer::{LexError, Token, tokenize};
use super::syntax::*;
use crate::diagnostic::{self, Diagnostic};
use crate::source::{FileId, Span};
use chumsky::input::{Stream, ValueInput};
use chumsky::prelude::*;

type Extra<'tok, 'src> = extra::Err<Rich<'tok, Token<'src>>>;

/// Parse a whole `.cal` text. Always returns a program holding every statement that
/// parsed; the diagnostics list the ones that did not.
pub fn parse(file: FileId, text: &str) -> (Program, Vec<Diagnostic>) {
    let (tokens, lex_errors) = tokenize(text);
    let mut diags: Vec<Diagnostic> = lex_errors
        .into_iter()
        .map(|(e, r)| lex_diagnostic(file, e, r))
        .collect();
    let mut statements = Vec::new();
    for segment in tokens.split(|(t, _)| *t == Token::Semi) {
        if segment.is_empty() || segment.iter().any(|(t, _)| *t == Token::Error) {
            continue; // empty statement, or already reported by the lexer
        }
        if let Some(d) = too_deep(file, segment) {
            diags.push(d);
            continue;
        }
        match parse_statement(file, text, segment) {
            Ok(stmt) if tree_depth(&stmt) > MAX_TREE_DEPTH => diags.push(
                Diagnostic::new(
                    diagnostic::E0501,
                    stmt.span(),
                    format!("this statement nests more than {MAX_TREE_DEPTH} operations deep"),
                )
                .with_hint("split it into several definitions"),
            ),
            Ok(stmt) => {
                check_params(&stmt, &mut diags);
                statements.push(stmt);
            }
            Err(errs) => diags.extend(errs),
        }
    }
    (Program { statements }, diags)
}

/// Parse one expression (an rcalc `-o` format field, an editor hover): the whole text
/// must be a single `E1`.
pub fn parse_expr(file: FileId, text: &str) -> Result<Expr, Vec<Diagnostic>> {
    let (tokens, lex_errors) = tokenize(text);
    if !lex_errors.is_empty() {
        return Err(lex_errors
            .into_iter()
            .map(|(e, r)| lex_diagnostic(file, e, r))
            .collect());
    }
    let eoi = eoi_span(&tokens);
    let stream = Stream::from_iter(
        tokens
            .iter()
            .map(|(t, r)| (*t, SimpleSpan::from(r.clone()))),
    )
    .map(eoi, |(t, s): (_, _)| (t, s));
    expr_parser(file)
        .then_ignore(end())
        .parse(stream)
        .into_result()
        .map_err(|errs| {
            errs.into_iter()
                .map(|e| syntax_diagnostic(file, text, &tokens, e))
                .collect()
        })
}

/// Parentheses nested deeper than this are refused before parsing: the parser, the
/// resolver and the evaluator recurse on them, and no real file comes close.
const MAX_PAREN_DEPTH: usize = 50;
/// Deepest statement syntax tree accepted (a sum of 1000 terms is this deep).
const MAX_TREE_DEPTH: usize = 1000;

/// Refuse, before parsing, statements whose tree could be too deep to walk: the
/// operator count bounds the depth. (Radiance's library peaks near 400.)
fn too_deep(file: FileId, segment: &[(Token<'_>, std::ops::Range<usize>)]) -> Option<Diagnostic> {
    let mut depth = 0usize;
    let mut operators = 0usize;
    for (t, r) in segment {
        match t {
            Token::LParen => depth += 1,
            Token::RParen => depth = depth.saturating_sub(1),
            Token::Plus | Token::Minus | Token::Star | Token::Slash | Token::Caret => {
                operators += 1;
                if operators > MAX_TREE_DEPTH {
                    return Some(
                        Diagnostic::new(
                            diagnostic::E0501,
                            Span::new(file, r.clone()),
                            format!("this statement has more than {MAX_TREE_DEPTH} operators"),
                        )
                        .with_hint("split it into several definitions"),
                    );
                }
            }
            _ => {}
        }
        if depth > MAX_PAREN_DEPTH {
            return Some(Diagnostic::new(
                diagnostic::E0501,
                Span::new(file, r.clone()),
                format!("parentheses nest more than {MAX_PAREN_DEPTH} deep"),
            ));
        }
    }
    None
}

/// The depth of a statement's tree, without recursion (the tree may be deep).
fn tree_depth(stmt: &Statement) -> usize {
    let body = match stmt {
        Statement::Definition(d) => &d.body,
        Statement::Output(o) => &o.body,
    };
    let mut max = 0;
    let mut stack = vec![(body, 1usize)];
    while let Some((e, d)) = stack.pop() {
        max = max.max(d);
        match &e.kind {
            ExprKind::Call { args, .. } => stack.extend(args.iter().map(|a| (a, d + 1))),
            ExprKind::Neg(x) | ExprKind::Paren(x) => stack.push((x, d + 1)),
            ExprKind::Binary { lhs, rhs, .. } => {
                stack.push((lhs, d + 1));
                stack.push((rhs, d + 1));
            }
            _ => {}
        }
    }
    max
}

fn eoi_span(segment: &[(Token<'_>, std::ops::Range<usize>)]) -> SimpleSpan {
    let end = segment.last().map(|(_, r)| r.end).unwrap_or(0);
    SimpleSpan::from(end..end)
}

fn parse_statement(
    file: FileId,
    text: &str,
    segment: &[(Token<'_>, std::ops::Range<usize>)],
) -> Result<Statement, Vec<Diagnostic>> {
    let eoi = eoi_span(segment);
    let stream = Stream::from_iter(
        segment
            .iter()
            .map(|(t, r)| (*t, SimpleSpan::from(r.clone())))
            .collect::<Vec<_>>(),
    )
    .map(eoi, |(t, s): (_, _)| (t, s));
    statement_parser(file)
        .then_ignore(end())
        .parse(stream)
        .into_result()
        .map_err(|errs| {
            errs.into_iter()
                .map(|e| syntax_diagnostic(file, text, segment, e))
                .collect()
        })
}

fn span(file: FileId, s: SimpleSpan) -> Span {
    Span::new(file, s.start..s.end)
}

fn ident<'tok, 'src: 'tok, I>(
    file: FileId,
) -> impl Parser<'tok, I, Ident, Extra<'tok, 'src>> + Clone
where
    I: ValueInput<'tok, Token = Token<'src>, Span = SimpleSpan>,
{
    select! { Token::Name(n) => n }
        .map_with(move |n: &str, e| Ident {
            name: n.to_string(),
            span: span(file, e.span()),
        })
        .labelled("a name")
}

fn statement_parser<'tok, 'src: 'tok, I>(
    file: FileId,
) -> impl Parser<'tok, I, Statement, Extra<'tok, 'src>>
where
    I: ValueInput<'tok, Token = Token<'src>, Span = SimpleSpan>,
{
    let expr = expr_parser(file);
    let output = select! { Token::Channel(n) => n }
        .map_with(move |n, e| (n, span(file, e.span())))
        .then_ignore(just(Token::Eq).labelled("'='"))
        .then(expr.clone())
        .map_with(move |((channel, channel_span), body), e| {
            Statement::Output(Output {
                channel,
                channel_span,
                body,
                span: span(file, e.span()),
            })
        });
    let params = ident(file)
        .separated_by(just(Token::Comma))
        .at_least(1)
        .collect::<Vec<_>>()
        .delimited_by(just(Token::LParen), just(Token::RParen).labelled("')'"));
    let kind = select! {
        Token::Eq => DefKind::Assign,
        Token::Colon => DefKind::Constant,
    }
    .labelled("'=' or ':'");
    let definition = ident(file)
        .then(params.or_not())
        .then(kind)
        .then(expr)
        .map_with(move |(((name, params), kind), body), e| {
            Statement::Definition(Definition {
                name,
                params,
                kind,
                body,
                span: span(file, e.span()),
            })
        });
    output.or(definition)
}

/// The expression grammar `E1`.
pub(crate) fn expr_parser<'tok, 'src: 'tok, I>(
    file: FileId,
) -> impl Parser<'tok, I, Expr, Extra<'tok, 'src>> + Clone
where
    I: ValueInput<'tok, Token = Token<'src>, Span = SimpleSpan>,
{
    recursive(move |e1| {
        let mk = move |kind, s: SimpleSpan| Expr {
            kind,
            span: span(file, s),
        };
        let paren = e1
            .clone()
            .delimited_by(just(Token::LParen), just(Token::RParen).labelled("')'"))
            .map_with(move |inner, e| mk(ExprKind::Paren(Box::new(inner)), e.span()));
        let args = e1
            .clone()
            .separated_by(just(Token::Comma))
            .at_least(1)
            .collect::<Vec<_>>()
            .delimited_by(just(Token::LParen), just(Token::RParen).labelled("')'"));
        let name_or_call = ident(file)
            .then(args.or_not())
            .map_with(move |(callee, args), e| match args {
                Some(args) => mk(ExprKind::Call { callee, args }, e.span()),
                None => mk(ExprKind::Name(callee), e.span()),
            });
        let leaf = select! {
            Token::Number(n) => ExprKind::Number(n),
            Token::Channel(c) => ExprKind::Channel(c),
        }
        .map_with(move |k, e| mk(k, e.span()));
        let e5 = choice((paren, name_or_call, leaf)).labelled("an expression");
        let e4 = choice((
            just(Token::Minus)
                .ignore_then(e5.clone())
                .map_with(move |x, e| mk(ExprKind::Neg(Box::new(x)), e.span())),
            just(Token::Plus).ignore_then(e5.clone()),
            e5,
        ));
        // E3: right-associative, so collect the chain and fold from the right.
        let e3 = e4
            .clone()
            .separated_by(just(Token::Caret))
            .at_least(1)
            .collect::<Vec<Expr>>()
            .map(|mut chain| {
                let mut acc = chain.pop().unwrap_or(Expr {
                    kind: ExprKind::Error,
                    span: Span::default(),
                });
                while let Some(base) = chain.pop() {
                    let s = base.span.to(acc.span);
                    acc = Expr {
                        kind: ExprKind::Binary {
                            op: BinOp::Pow,
                            lhs: Box::new(base),
                            rhs: Box::new(acc),
                        },
                        span: s,
                    };
                }
                acc
            });
        let binary = |lhs: Expr, (op, rhs): (BinOp, Expr)| {
            let s = lhs.span.to(rhs.span);
            Expr {
                kind: ExprKind::Binary {
                    op,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                span: s,
            }
        };
        let mulop = select! { Token::Star => BinOp::Mul, Token::Slash => BinOp::Div };
        let e2 = e3.clone().foldl(mulop.then(e3).repeated(), binary);
        let addop = select! { Token::Plus => BinOp::Add, Token::Minus => BinOp::Sub };
        e2.clone().foldl(addop.then(e2).repeated(), binary)
    })
}

/// Radiance refuses parameter names with a context mark (`egetdefn`: "illegal
/// parameter name"): a parameter is always local to its function.
fn check_params(stmt: &Statement, diags: &mut Vec<Diagnostic>) {
    if let Statement::Definition(Definition {
        params: Some(ps), ..
    }) = stmt
    {
        for p in ps.iter().filter(|p| p.name.contains('`')) {
            diags.push(
                Diagnostic::new(
                    diagnostic::E0502,
                    p.span,
                    format!("parameter name '{}' contains a context mark '`'", p.name),
                )
                .with_hint("parameters are always local; remove the back-quote"),
            );
        }
    }
}

fn lex_diagnostic(file: FileId, e: LexError, r: std::ops::Range<usize>) -> Diagnostic {
    let span = Span::new(file, r);
    let d = Diagnostic::new(diagnostic::E0501, span, e.message());
    match e {
        LexError::UnterminatedComment => {
            d.with_hint("comments '{ ... }' nest: every '{' needs its own '}'")
        }
        LexError::BadNumber => {
            d.with_hint("write a digit before or after the '.', e.g. '0.5' or '.5'")
        }
        LexError::MissingExponent => d.with_hint("write the exponent's digits, e.g. '1e3'"),
        LexError::UnexpectedChar => d.with_hint(
            "calcomp has only + - * / ^ ( ) , ; = : operators; use if(), and(), or() for logic",
        ),
    }
}

fn syntax_diagnostic(
    file: FileId,
    text: &str,
    segment: &[(Token<'_>, std::ops::Range<usize>)],
    e: Rich<'_, Token<'_>>,
) -> Diagnostic {
    let s = e.span();
    let found = match e.found() {
        Some(Token::Number(n)) => format!("the number {n}"),
        Some(Token::Name(n)) => format!("the name '{n}'"),
        Some(t) => format!("'{t}'"),
        None => "the end of the statement".to_string(),
    };
    let mut expected: Vec<String> = e.expected().map(|x| x.to_string()).collect();
    expected.sort();
    expected.dedup();
    let message = if expected.is_empty() {
        format!("unexpected {found}")
    } else {
        format!("expected {}, found {found}", expected.join(" or "))
    };
    let mut d = Diagnostic::new(diagnostic::E0501, Span::new(file, s.start..s.end), message);
    if e.found().is_none() && !segment.is_empty() {
        // Point at the last token rather than nowhere.
        let last = segment[segment.len() - 1].1.clone();
        d.span = Span::new(file, last);
    }
    let after_operand = text
        .get(..s.start)
        .map(str::trim_end)
        .is_some_and(|t| t.ends_with(|c: char| c.is_ascii_alphanumeric() || c == ')'));
    if matches!(e.found(), Some(Token::Name(_))) && after_operand {
        d = d.with_hint("is a ';' missing between two statements?");
    }
    if matches!(e.found(), Some(Token::RParen))
        && text.get(s.start.saturating_sub(1)..s.start) == Some("(")
    {
        d = d.with_hint("calcomp functions take at least one argument: 'f()' is not allowed");
    }
    if matches!(e.found(), Some(Token::Minus | Token::Plus)) {
        d = d.with_hint("calcomp allows one sign only: write '-(-x)' rather than '--x'");
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Program {
        let (prog, diags) = parse(FileId(0), s);
        assert!(diags.is_empty(), "{s}: {diags:?}");
        prog
    }

    fn errs(s: &str) -> usize {
        parse(FileId(0), s).1.len()
    }

    fn show(e: &Expr) -> String {
        match &e.kind {
            ExprKind::Number(n) => format!("{n}"),
            ExprKind::Channel(c) => format!("${c}"),
            ExprKind::Name(i) => i.name.clone(),
            ExprKind::Call { callee, args } => format!(
                "{}({})",
                callee.name,
                args.iter().map(show).collect::<Vec<_>>().join(",")
            ),
            ExprKind::Neg(x) => format!("(-{})", show(x)),
            ExprKind::Paren(x) => show(x),
            ExprKind::Binary { op, lhs, rhs } => {
                format!("({}{}{})", show(lhs), op.symbol(), show(rhs))
            }
            ExprKind::Error => "!".into(),
        }
    }

    fn body(s: &str) -> String {
        match &p(s).statements[0] {
            Statement::Definition(d) => show(&d.body),
            Statement::Output(o) => show(&o.body),
        }
    }

    #[test]
    fn precedence_and_associativity_follow_radiance() {
        assert_eq!(body("x = -2^2"), "((-2)^2)");
        assert_eq!(body("x = 2^3^2"), "(2^(3^2))");
        assert_eq!(body("x = 8/2/2"), "((8/2)/2)");
        assert_eq!(body("x = 2-3-4"), "((2-3)-4)");
        assert_eq!(body("x = 1+2*3^-2"), "(1+(2*(3^(-2))))");
        assert_eq!(body("x = +a*-b"), "(a*(-b))");
        assert_eq!(body("$3 = f(a, g, $1)"), "f(a,g,$1)");
    }

    #[test]
    fn statements_and_definitions() {
        let prog = p("a = 1; b : 2;; f(x, y) = x*y; $1 = f(a, b);");
        assert_eq!(prog.statements.len(), 4);
        match &prog.statements[2] {
            Statement::Definition(d) => {
                assert_eq!(d.params.as_ref().map(Vec::len), Some(2));
                assert_eq!(d.kind, DefKind::Assign);
            }
            _ => panic!("expected a definition"),
        }
    }

    #[test]
    fn syntax_errors_radiance_rejects() {
        for s in [
            "x = --2", "x = +-2", "x = f()", "f() = 1", "x = 1 2", "x = (1", "x 1", "$1 : 2",
        ] {
            assert!(errs(s) > 0, "{s} should be an error");
        }
    }

    #[test]
    fn one_bad_statement_does_not_hide_the_next() {
        let (prog, diags) = parse(FileId(0), "a = 1 +; b = 2; c = * 3; d = 4");
        assert_eq!(diags.len(), 2);
        assert_eq!(prog.statements.len(), 2);
    }

    #[test]
    fn spans_point_into_the_text() {
        let text = "abc = foo(1, 2)";
        match &p(text).statements[0] {
            Statement::Definition(d) => {
                assert_eq!(&text[d.name.span.range()], "abc");
                assert_eq!(&text[d.body.span.range()], "foo(1, 2)");
                assert_eq!(d.span.range(), 0..text.len());
            }
            _ => panic!(),
        }
    }
}
