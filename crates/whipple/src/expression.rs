//! Rider torques written as expressions of time and the state, such as `0.5*sin(2*t)`,
//! `1e3*t` or `10*lean + 20*lean_rate`: parsed once, checked for unknown names, and turned into
//! a [`TorqueFn`] for [`crate::nonlinear::SimulationSettings`]. The command line and the web API read the
//! same language.
//!
//! The language: numbers in decimal or scientific notation (`2`, `0.5`, `.5`, `2.5e-1`,
//! `1E3`); the names of [`VARIABLES`]; the constants `pi` (also `PI`, `π`), `e` (also `E`) and
//! `tau` (also `TAU`); `+ - * /` and `^` (power, right-associative, binding tighter than a
//! leading minus: `-2^2` is −4); parentheses; the functions of [`FUNCTIONS`] (one argument) and
//! `atan2(y, x)`, `min(a, b)`, `max(a, b)`. The parser is written here rather than taken from
//! an expression library so that every message points at a column of what was typed, numbers
//! take scientific notation, and both the length and the nesting depth are bounded (no
//! recursion a hostile input can drive deep).
//!
//! The same parser evaluates the arithmetic in BicycleParameters and HumanControl `.txt` values
//! ([`evaluate_constant`]): there no variable is known, and the names are those such files use
//! (`pi`, `sqrt`, `sin`, `cos`, `tan`, `abs`, `deg2rad`), with the same precedence.
//!
//! ```
//! use whipple::advanced::nonlinear::TorqueExpression;
//! let torque = TorqueExpression::parse("10*lean + 20*lean_rate")?;
//! assert_eq!(torque.text(), "10*lean + 20*lean_rate");
//! assert!(TorqueExpression::parse("2*foo").is_err());
//! assert!(TorqueExpression::parse("2.5e-1*sin(3*t)").is_ok());
//! # Ok::<(), whipple::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::nonlinear::StateView;
use crate::nonlinear::TorqueFn;

/// The names an expression may use: time t \[s\], the lean, steer and yaw angles \[rad\], their
/// rates [rad/s] and the forward speed [m/s].
pub(crate) const VARIABLES: [&str; 7] = [
    "lean",
    "lean_rate",
    "speed",
    "steer",
    "steer_rate",
    "t",
    "yaw",
];

/// The functions of one argument an expression may call (`log` is the natural logarithm, as
/// `ln`).
pub(crate) const FUNCTIONS: [&str; 26] = [
    "abs", "acos", "acosh", "asin", "asinh", "atan", "atanh", "cbrt", "ceil", "cos", "cosh", "exp",
    "floor", "fract", "ln", "log", "log10", "log2", "round", "sign", "signum", "sin", "sinh",
    "sqrt", "tan", "tanh",
];

/// Longest expression accepted, in bytes.
pub const MAX_LENGTH: usize = 1000;

/// Deepest nesting of parentheses, function calls and signs accepted.
pub const MAX_DEPTH: usize = 64;

/// One step of the compiled (postfix) program.
#[derive(Debug, Clone, Copy)]
enum Op {
    Number(f64),
    Variable(usize),
    Negate,
    Add,
    Subtract,
    Multiply,
    Divide,
    Power,
    Call(fn(f64) -> f64),
    Call2(fn(f64, f64) -> f64),
}

/// A parsed torque expression [N m].
#[derive(Debug, Clone)]
pub struct TorqueExpression {
    text: String,
    program: Vec<Op>,
    /// Most values on the evaluation stack at once.
    stack: usize,
}

fn value(slot: usize, t: f64, s: &StateView) -> f64 {
    match slot {
        0 => s.lean,
        1 => s.lean_rate,
        2 => s.speed,
        3 => s.steer,
        4 => s.steer_rate,
        5 => t,
        _ => s.yaw,
    }
}

fn unary(name: &str) -> Option<fn(f64) -> f64> {
    Some(match name {
        "abs" => f64::abs,
        "acos" => crate::math::acos,
        "acosh" => crate::math::acosh,
        "asin" => crate::math::asin::<f64>,
        "asinh" => crate::math::asinh,
        "atan" => crate::math::atan::<f64>,
        "atanh" => crate::math::atanh,
        "cbrt" => crate::math::cbrt,
        "ceil" => f64::ceil,
        "cos" => crate::math::cos::<f64>,
        "cosh" => crate::math::cosh,
        "exp" => crate::math::exp,
        "floor" => f64::floor,
        "fract" => f64::fract,
        "ln" | "log" => crate::math::ln,
        "log10" => crate::math::log10,
        "log2" => crate::math::log2,
        "round" => f64::round,
        // signum(0) is 1 in Rust; a rider's sign function is 0 at 0.
        "sign" | "signum" => |x: f64| if x == 0.0 { 0.0 } else { x.signum() },
        "sin" => crate::math::sin::<f64>,
        "sinh" => crate::math::sinh,
        "sqrt" => f64::sqrt,
        "tan" => crate::math::tan::<f64>,
        "tanh" => crate::math::tanh,
        _ => return None,
    })
}

fn binary(name: &str) -> Option<fn(f64, f64) -> f64> {
    Some(match name {
        "atan2" => crate::math::atan2::<f64>,
        "max" => f64::max,
        "min" => f64::min,
        _ => return None,
    })
}

fn constant(name: &str) -> Option<f64> {
    Some(match name {
        "pi" | "PI" | "π" => std::f64::consts::PI,
        "e" | "E" => std::f64::consts::E,
        "tau" | "TAU" | "τ" => std::f64::consts::TAU,
        _ => return None,
    })
}

/// The functions a parameter file's value may call (what MATLAB's `str2num` of such files
/// evaluates).
fn file_function(name: &str) -> Option<fn(f64) -> f64> {
    Some(match name {
        "abs" => f64::abs,
        "cos" => crate::math::cos::<f64>,
        "deg2rad" => f64::to_radians,
        "sin" => crate::math::sin::<f64>,
        "sqrt" => f64::sqrt,
        "tan" => crate::math::tan::<f64>,
        _ => return None,
    })
}

/// The one constant a parameter file's value may name.
fn file_constant(name: &str) -> Option<f64> {
    (name == "pi").then_some(std::f64::consts::PI)
}

/// No function of two arguments in a parameter file.
fn no_binary(_: &str) -> Option<fn(f64, f64) -> f64> {
    None
}

/// Looks up a function of one argument by name.
type UnaryLookup = fn(&str) -> Option<fn(f64) -> f64>;
/// Looks up a function of two arguments by name.
type BinaryLookup = fn(&str) -> Option<fn(f64, f64) -> f64>;

/// The names one use of the language knows: the grammar and precedence are the same for all.
struct Dialect {
    variables: &'static [&'static str],
    unary: UnaryLookup,
    binary: BinaryLookup,
    constant: fn(&str) -> Option<f64>,
    /// What an unknown name's message lists as known.
    known: fn() -> String,
    /// The argument of the example call in the message about a call without parentheses.
    example_argument: &'static str,
}

/// Rider torques: time, the state, every function and constant.
const TORQUE: Dialect = Dialect {
    variables: &VARIABLES,
    unary,
    binary,
    constant,
    known: || {
        format!(
            "the variables are {}; the functions {}, atan2, min, max; the constants pi, e, tau",
            VARIABLES.join(", "),
            FUNCTIONS.join(", ")
        )
    },
    example_argument: "t",
};

/// Values in BicycleParameters and HumanControl `.txt` files: no variables.
const FILE_VALUE: Dialect = Dialect {
    variables: &[],
    unary: file_function,
    binary: no_binary,
    constant: file_constant,
    known: || "the functions are abs, cos, deg2rad, sin, sqrt, tan; the constant pi".into(),
    example_argument: "2",
};

#[derive(Debug, Clone, Copy, PartialEq)]
enum Token<'a> {
    Number(f64),
    Name(&'a str),
    Symbol(char),
}

/// A token and the 1-based column (in characters) where it starts.
type Located<'a> = (Token<'a>, usize);

fn describe(token: Option<&Located<'_>>) -> String {
    match token {
        None => "the end".into(),
        Some((Token::Number(_), column)) => format!("a number at column {column}"),
        Some((Token::Name(name), column)) => format!("`{name}` at column {column}"),
        Some((Token::Symbol(c), column)) => format!("`{c}` at column {column}"),
    }
}

fn tokens(text: &str) -> std::result::Result<Vec<Located<'_>>, String> {
    let mut out = Vec::new();
    let chars: Vec<(usize, char)> = text.char_indices().collect();
    let mut i = 0;
    while i < chars.len() {
        let (start, c) = chars[i];
        let column = i + 1;
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            // digits [. digits] [(e|E) [+|-] digits], the exponent only when digits follow.
            let mut j = i;
            let digits = |j: &mut usize| {
                while *j < chars.len() && chars[*j].1.is_ascii_digit() {
                    *j += 1;
                }
            };
            digits(&mut j);
            if j < chars.len() && chars[j].1 == '.' {
                j += 1;
                digits(&mut j);
            }
            if j < chars.len() && matches!(chars[j].1, 'e' | 'E') {
                let mut k = j + 1;
                if k < chars.len() && matches!(chars[k].1, '+' | '-') {
                    k += 1;
                }
                if k < chars.len() && chars[k].1.is_ascii_digit() {
                    digits(&mut k);
                    j = k;
                }
            }
            let end = chars.get(j).map_or(text.len(), |&(b, _)| b);
            let literal = &text[start..end];
            let x: f64 = literal
                .parse()
                .map_err(|_| format!("`{literal}` at column {column} is not a number"))?;
            if !x.is_finite() {
                return Err(format!(
                    "the number `{literal}` at column {column} is too large for a double"
                ));
            }
            out.push((Token::Number(x), column));
            i = j;
        } else if c.is_alphabetic() || c == '_' {
            let mut j = i;
            while j < chars.len() && (chars[j].1.is_alphanumeric() || chars[j].1 == '_') {
                j += 1;
            }
            let end = chars.get(j).map_or(text.len(), |&(b, _)| b);
            out.push((Token::Name(&text[start..end]), column));
            i = j;
        } else if "+-*/^(),".contains(c) {
            out.push((Token::Symbol(c), column));
            i += 1;
        } else {
            return Err(format!(
                "`{}` at column {column} is not part of the expression language (numbers, names, + - * / ^, parentheses, functions)",
                c.escape_debug()
            ));
        }
    }
    Ok(out)
}

/// Recursive descent over the tokens, bounded by [`MAX_DEPTH`], emitting postfix code.
struct Parser<'a> {
    dialect: &'a Dialect,
    tokens: Vec<Located<'a>>,
    at: usize,
    program: Vec<Op>,
    depth: usize,
}

type Step = std::result::Result<(), String>;

impl<'a> Parser<'a> {
    fn peek(&self) -> Option<&Located<'a>> {
        self.tokens.get(self.at)
    }

    fn peek_symbol(&self, symbol: char) -> bool {
        matches!(self.peek(), Some((Token::Symbol(c), _)) if *c == symbol)
    }

    fn deeper(&mut self) -> Step {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(format!(
                "nested more than {MAX_DEPTH} levels deep at {}",
                describe(self.peek())
            ));
        }
        Ok(())
    }

    fn expect(&mut self, symbol: char, context: &str) -> Step {
        if self.peek_symbol(symbol) {
            self.at += 1;
            Ok(())
        } else {
            Err(format!(
                "expected `{symbol}` {context}, found {}",
                describe(self.peek())
            ))
        }
    }

    /// sum := product (('+' | '-') product)*
    fn sum(&mut self) -> Step {
        self.product()?;
        loop {
            let op = match self.peek() {
                Some((Token::Symbol('+'), _)) => Op::Add,
                Some((Token::Symbol('-'), _)) => Op::Subtract,
                _ => return Ok(()),
            };
            self.at += 1;
            self.product()?;
            self.program.push(op);
        }
    }

    /// product := signed (('*' | '/') signed)*
    fn product(&mut self) -> Step {
        self.signed()?;
        loop {
            let op = match self.peek() {
                Some((Token::Symbol('*'), _)) => Op::Multiply,
                Some((Token::Symbol('/'), _)) => Op::Divide,
                _ => return Ok(()),
            };
            self.at += 1;
            self.signed()?;
            self.program.push(op);
        }
    }

    /// signed := ('-' | '+') signed | power
    fn signed(&mut self) -> Step {
        self.deeper()?;
        let result = match self.peek() {
            Some((Token::Symbol('-'), _)) => {
                self.at += 1;
                self.signed().map(|()| self.program.push(Op::Negate))
            }
            Some((Token::Symbol('+'), _)) => {
                self.at += 1;
                self.signed()
            }
            _ => self.power(),
        };
        self.depth -= 1;
        result
    }

    /// power := primary ('^' signed)?   (right-associative; the exponent may carry a sign)
    fn power(&mut self) -> Step {
        self.primary()?;
        if self.peek_symbol('^') {
            self.at += 1;
            self.signed()?;
            self.program.push(Op::Power);
        }
        Ok(())
    }

    /// primary := number | variable | constant | function '(' sum [',' sum] ')' | '(' sum ')'
    fn primary(&mut self) -> Step {
        let Some(&(token, column)) = self.peek() else {
            return Err("the expression ends where a number, a name or `(` was expected".into());
        };
        self.at += 1;
        match token {
            Token::Number(x) => self.program.push(Op::Number(x)),
            Token::Symbol('(') => {
                self.deeper()?;
                self.sum()?;
                self.expect(')', &format!("to close the `(` at column {column}"))?;
                self.depth -= 1;
            }
            Token::Symbol(c) => {
                return Err(format!(
                    "`{c}` at column {column} where a number, a name or `(` was expected"
                ));
            }
            Token::Name(name) => {
                let call = self.peek_symbol('(');
                let d = self.dialect;
                if let Some(slot) = d.variables.iter().position(|v| *v == name) {
                    self.program.push(Op::Variable(slot));
                } else if let (false, Some(x)) = (call, (d.constant)(name)) {
                    self.program.push(Op::Number(x));
                } else if let (true, Some(f)) = (call, (d.unary)(name)) {
                    self.arguments(name, column, 1)?;
                    self.program.push(Op::Call(f));
                } else if let (true, Some(f)) = (call, (d.binary)(name)) {
                    self.arguments(name, column, 2)?;
                    self.program.push(Op::Call2(f));
                } else if call && (d.constant)(name).is_some() {
                    return Err(format!(
                        "`{name}` at column {column} is a constant, not a function"
                    ));
                } else if (d.unary)(name).is_some() || (d.binary)(name).is_some() {
                    return Err(format!(
                        "the function `{name}` at column {column} needs its argument in parentheses, as `{name}({})`",
                        d.example_argument
                    ));
                } else {
                    return Err(format!(
                        "unknown name `{name}` at column {column} ({})",
                        (d.known)()
                    ));
                }
            }
        }
        // Two operands side by side (`2 t`, `2(t)`, `t sin(t)`): say so here rather than
        // later as a stray token.
        if let Some((Token::Number(_) | Token::Name(_), _)) | Some((Token::Symbol('('), _)) =
            self.peek()
        {
            return Err(format!(
                "{} follows an operand without an operator between them (write `*` for a product)",
                describe(self.peek())
            ));
        }
        Ok(())
    }

    fn arguments(&mut self, name: &str, column: usize, count: usize) -> Step {
        self.deeper()?;
        self.at += 1; // '('
        for k in 0..count {
            if k > 0 {
                self.expect(
                    ',',
                    &format!("between the arguments of `{name}` (it takes {count})"),
                )?;
            }
            self.sum()?;
        }
        if self.peek_symbol(',') {
            return Err(format!(
                "`{name}` at column {column} takes {count} argument{}, found more",
                if count == 1 { "" } else { "s" }
            ));
        }
        self.expect(
            ')',
            &format!("to close the call of `{name}` at column {column}"),
        )?;
        self.depth -= 1;
        Ok(())
    }
}

/// The stack depth `program` needs (it is well formed by construction).
fn stack_depth(program: &[Op]) -> usize {
    let (mut depth, mut most) = (0usize, 0usize);
    for op in program {
        match op {
            Op::Number(_) | Op::Variable(_) => depth += 1,
            Op::Negate | Op::Call(_) => {}
            _ => depth = depth.saturating_sub(1),
        }
        most = most.max(depth);
    }
    most
}

fn run(program: &[Op], stack: &mut Vec<f64>, variables: &[f64]) -> f64 {
    stack.clear();
    for op in program {
        let x = match *op {
            Op::Number(x) => x,
            Op::Variable(slot) => variables.get(slot).copied().unwrap_or(f64::NAN),
            Op::Negate => -stack.pop().unwrap_or(f64::NAN),
            Op::Call(f) => f(stack.pop().unwrap_or(f64::NAN)),
            _ => {
                let b = stack.pop().unwrap_or(f64::NAN);
                let a = stack.pop().unwrap_or(f64::NAN);
                match *op {
                    Op::Add => a + b,
                    Op::Subtract => a - b,
                    Op::Multiply => a * b,
                    Op::Divide => a / b,
                    Op::Power => crate::math::powf(a, b),
                    Op::Call2(f) => f(a, b),
                    _ => f64::NAN,
                }
            }
        };
        stack.push(x);
    }
    // A well-formed program leaves exactly one value.
    if stack.len() == 1 { stack[0] } else { f64::NAN }
}

/// Why a text is not an expression of a dialect.
enum Refusal {
    /// Longer than [`MAX_LENGTH`] bytes (its length).
    TooLong(usize),
    /// Nothing but white space.
    Empty,
    /// What is wrong, and at which column.
    Unreadable(String),
}

/// Parses `text` in `dialect` into postfix code and the stack depth it needs.
fn compile(text: &str, dialect: &Dialect) -> std::result::Result<(Vec<Op>, usize), Refusal> {
    if text.len() > MAX_LENGTH {
        return Err(Refusal::TooLong(text.len()));
    }
    let tokens = tokens(text).map_err(Refusal::Unreadable)?;
    if tokens.is_empty() {
        return Err(Refusal::Empty);
    }
    let mut parser = Parser {
        dialect,
        tokens,
        at: 0,
        program: Vec::new(),
        depth: 0,
    };
    parser.sum().map_err(Refusal::Unreadable)?;
    if let Some(rest) = parser.peek() {
        let why = match rest {
            (Token::Symbol(')'), column) => {
                format!("the `)` at column {column} closes no `(`")
            }
            _ => format!("{} where an operator was expected", describe(Some(rest))),
        };
        return Err(Refusal::Unreadable(why));
    }
    let stack = stack_depth(&parser.program);
    Ok((parser.program, stack))
}

/// The value of a number written as arithmetic in a BicycleParameters or HumanControl `.txt`
/// file (`pi/10`, `-2^2`, `sqrt(2)*0.5`, `deg2rad(18)`): the torque language's grammar and
/// precedence, without variables, with the names such files use. The error says what is wrong
/// and at which column of `text`; the caller names the field.
pub(crate) fn evaluate_constant(text: &str) -> std::result::Result<f64, String> {
    let (program, depth) = compile(text, &FILE_VALUE).map_err(|refusal| match refusal {
        Refusal::TooLong(n) => format!("it is {n} bytes long, more than the limit of {MAX_LENGTH}"),
        Refusal::Empty => "it is empty".into(),
        Refusal::Unreadable(why) => why,
    })?;
    let v = run(&program, &mut Vec::with_capacity(depth), &[]);
    if !v.is_finite() {
        return Err(format!("the result is not a finite number ({v})"));
    }
    Ok(v)
}

impl TorqueExpression {
    /// Parses `text`; its names must be among `VARIABLES`, the constants and the functions,
    /// and it must evaluate to a finite number at rest (every variable zero). The error's rule
    /// says what is wrong and at which column.
    pub fn parse(text: &str) -> Result<Self> {
        let invalid = |rule: String| Error::InvalidArgument {
            what: "torque expression",
            rule,
        };
        // Quoted in messages with its control characters escaped, so that it cannot break the
        // message's lines.
        let shown = text.escape_debug().to_string();
        let (program, stack) = compile(text, &TORQUE).map_err(|refusal| {
            invalid(match refusal {
                Refusal::TooLong(n) => {
                    format!("is {n} bytes long, more than the limit of {MAX_LENGTH}")
                }
                Refusal::Empty => {
                    "is empty (write 0 for no torque, or an expression such as `0.5*sin(2*t)`)"
                        .into()
                }
                Refusal::Unreadable(why) => format!("cannot read `{shown}`: {why}"),
            })
        })?;
        let expression = TorqueExpression {
            text: text.to_string(),
            stack,
            program,
        };
        let at_rest = expression.eval(0.0, &StateView::default());
        if !at_rest.is_finite() {
            return Err(invalid(format!(
                "`{shown}` is not a finite number at rest (t = 0, every angle and rate 0): {at_rest}"
            )));
        }
        Ok(expression)
    }

    /// The text it was parsed from.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The torque at time t \[s\] in state s \[N m\]; NaN or an infinity where the expression is
    /// not finite there (`1/(t - 0.5)` at t = 0.5, `sqrt(0.5 - t)` after it).
    pub fn eval(&self, t: f64, s: &StateView) -> f64 {
        let variables: [f64; VARIABLES.len()] = std::array::from_fn(|slot| value(slot, t, s));
        let mut stack = Vec::with_capacity(self.stack);
        run(&self.program, &mut stack, &variables)
    }

    /// The expression as a rider input of a simulation.
    pub fn into_torque(self) -> TorqueFn {
        Box::new(move |t: f64, s: &StateView| self.eval(t, s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at_rest(text: &str) -> f64 {
        match TorqueExpression::parse(text) {
            Ok(e) => e.eval(0.0, &StateView::default()),
            Err(e) => panic!("{text}: {e}"),
        }
    }

    fn rule(text: &str) -> String {
        match TorqueExpression::parse(text) {
            Err(Error::InvalidArgument { what, rule }) => {
                assert_eq!(what, "torque expression");
                rule
            }
            other => panic!("{text}: {other:?}"),
        }
    }

    #[test]
    fn evaluates_with_the_state() -> Result<()> {
        let torque = TorqueExpression::parse("-10*lean - 2*lean_rate + t*speed + 0*yaw")?;
        let s = StateView {
            lean: 0.1,
            lean_rate: -0.5,
            speed: 4.0,
            ..StateView::default()
        };
        assert!((torque.eval(2.0, &s) - (-1.0 + 1.0 + 8.0)).abs() < 1e-15);
        Ok(())
    }

    /// `1e3*t` and `2.5e-1*sin(3*t)` were refused with the expression library's
    /// internal message ("we have 1 ops and 3 node").
    #[test]
    fn torque_expressions_take_scientific_notation() -> Result<()> {
        let s = StateView::default();
        assert_eq!(TorqueExpression::parse("1e3*t")?.eval(2.0, &s), 2000.0);
        let x = TorqueExpression::parse("2.5e-1*sin(3*t)")?.eval(0.5, &s);
        assert!((x - 0.25 * crate::math::sin(1.5f64)).abs() < 1e-16);
        assert_eq!(at_rest("1E+2"), 100.0);
        assert_eq!(at_rest(".5e1"), 5.0);
        assert_eq!(at_rest("2.e0"), 2.0);
        // `e` alone is Euler's number; `2e` is not a number, and a product needs its `*`.
        assert_eq!(at_rest("2*e"), 2.0 * std::f64::consts::E);
        assert!(rule("2e").contains("without an operator"));
        Ok(())
    }

    #[test]
    fn follows_the_usual_precedence() {
        assert_eq!(at_rest("1 + 2*3"), 7.0);
        assert_eq!(at_rest("2^3^2"), 512.0);
        assert_eq!(at_rest("-2^2"), -4.0);
        assert_eq!(at_rest("2^-1"), 0.5);
        assert_eq!(at_rest("(1 + 2)*3"), 9.0);
        assert_eq!(at_rest("8/2/2"), 2.0);
        assert_eq!(at_rest("1 - 2 - 3"), -4.0);
        assert_eq!(at_rest("--1"), 1.0);
        assert_eq!(at_rest("max(1, min(2, 3)) + atan2(0, 1)"), 2.0);
        assert!((at_rest("cos(pi)") + 1.0).abs() < 1e-15);
        assert_eq!(at_rest("sign(0)"), 0.0);
    }

    /// Parameter-file values use the same grammar and precedence as torques: `-2^2` is −4
    /// in both, `-` and `/` associate to the left and `^` to the right; only the names differ
    /// (no variables, `deg2rad`, only `pi`).
    #[test]
    fn file_values_share_the_grammar() {
        let value = |text: &str| match evaluate_constant(text) {
            Ok(v) => v,
            Err(e) => panic!("{text}: {e}"),
        };
        for text in [
            "-2^2",
            "2^-1",
            "2^3^2",
            "1 - 2 - 3",
            "8/2/2",
            "--1",
            "(1 + 2)*3",
        ] {
            assert_eq!(value(text), at_rest(text), "{text}");
        }
        assert_eq!(value("-2^2"), -4.0);
        assert_eq!(value("2^3^2"), 512.0);
        assert_eq!(value("8/2/2"), 2.0);
        assert_eq!(value("1 - 2 - 3"), -4.0);
        assert_eq!(value("deg2rad(180)"), std::f64::consts::PI);
        assert_eq!(value("pi/10"), std::f64::consts::PI / 10.0);
        for (text, expected) in [
            ("t", "unknown name `t` at column 1"),
            ("e", "unknown name `e` at column 1"),
            ("exp(1)", "unknown name `exp`"),
            ("sqrt 2", "needs its argument in parentheses, as `sqrt(2)`"),
            ("1/0", "not a finite number"),
            ("1 +", "the expression ends where"),
            ("2 3", "follows an operand"),
            ("", "empty"),
        ] {
            match evaluate_constant(text) {
                Ok(v) => panic!("{text}: accepted as {v}"),
                Err(got) => assert!(got.contains(expected), "{text}: {got}"),
            }
        }
        let deep = format!("{}1{}", "(".repeat(400), ")".repeat(400));
        assert!(evaluate_constant(&deep).is_err());
    }

    /// Every message names the place and never an internal detail of the parser.
    #[test]
    fn refuses_bad_expressions_by_rule() {
        for (text, expected) in [
            (
                "sin(t",
                "expected `)` to close the call of `sin` at column 1, found the end",
            ),
            ("2*foo", "unknown name `foo` at column 3"),
            ("1/t", "not a finite number at rest"),
            (
                "1+*2",
                "`*` at column 3 where a number, a name or `(` was expected",
            ),
            ("(1", "to close the `(` at column 1"),
            ("1)", "the `)` at column 2 closes no `(`"),
            ("2 t", "`t` at column 3 follows an operand"),
            ("sin t", "needs its argument in parentheses"),
            ("min(1)", "expected `,` between the arguments of `min`"),
            ("sin(1, 2)", "takes 1 argument, found more"),
            ("1e999", "too large for a double"),
            ("1 # 2", "`#` at column 3 is not part of"),
            ("", "is empty"),
            ("   ", "is empty"),
            ("t +", "the expression ends where"),
        ] {
            let got = rule(text);
            assert!(got.contains(expected), "{text}: {got}");
            assert!(!got.contains("node") && !got.contains("Operator"), "{got}");
        }
        assert!(TorqueExpression::parse(&"1+".repeat(600)).is_err());
    }

    /// Deep nesting is refused with a message instead of exhausting the stack.
    #[test]
    fn nesting_is_bounded() {
        let deep = format!("{}t{}", "(".repeat(400), ")".repeat(400));
        assert!(rule(&deep).contains("nested more than"));
        let signs = format!("{}t", "-".repeat(900));
        assert!(rule(&signs).contains("nested more than"));
        let fine = format!("{}t{}", "(".repeat(30), ")".repeat(30));
        assert_eq!(at_rest(&fine), 0.0);
    }

    /// A control character in an expression is escaped in the message.
    #[test]
    fn messages_escape_control_characters() {
        let got = rule("1+\n*2");
        assert!(!got.contains('\n'), "{got}");
    }

    /// Non-finite values during a run come out of `eval` as they are (the simulation reports
    /// them).
    #[test]
    fn non_finite_values_are_returned_as_they_are() -> Result<()> {
        let s = StateView::default();
        let pole = TorqueExpression::parse("1/(t-0.5)")?;
        assert!(pole.eval(0.5, &s).is_infinite());
        let root = TorqueExpression::parse("sqrt(0.5-t)")?;
        assert!(root.eval(0.75, &s).is_nan());
        Ok(())
    }
}
