//! Height-field expressions `z = f(x, y)`: a small parser and an evaluator that also gives
//! exact first and second derivatives along a line (forward-mode, second order).
//!
//! Grammar (usual precedence; `^` is right-associative and binds tighter than unary minus,
//! so `-x^2 = -(x^2)`):
//! ```text
//! expr  = term (("+" | "-") term)*
//! term  = unary (("*" | "/") unary)*
//! unary = ("-" | "+") unary | power
//! power = atom ("^" unary)?
//! atom  = number | "x" | "y" | "pi" | "e" | func "(" expr ")" | "(" expr ")"
//! func  = sin | cos | tan | exp | ln | sqrt | abs
//! ```
//! Limits: at most [`MAX_LENGTH`](crate::expr::MAX_LENGTH) bytes of source and [`MAX_DEPTH`](crate::expr::MAX_DEPTH) levels of nesting
//! (parentheses, function calls, signs and powers), so parsing never exhausts the stack.
//! The parser writes a postfix program (no tree), so evaluating and dropping an expression
//! is a loop, and every analysis is linear in its length.
//!
//! Written here rather than taken from a crate because sectioning needs exact curvature of
//! the section curve, i.e. second derivatives of `f` along the section, which the
//! permissively licensed expression crates do not provide.
//!
//! Entry points: [`Expr::parse`](crate::expr::Expr::parse), [`Expr::eval`](crate::expr::Expr::eval), [`Expr::eval_along`](crate::expr::Expr::eval_along).

use crate::error::{GeomError, Result};

/// Most bytes of source an expression may have.
pub const MAX_LENGTH: usize = 10_000;
/// Most levels of nesting an expression may have: a parenthesis or a function call counts
/// two (its argument is a new term), a power's exponent one, a run of signs one.
pub const MAX_DEPTH: usize = 200;

/// A parsed expression in the variables `x` and `y`.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    /// The program in postfix order.
    program: Vec<Instr>,
    /// Largest stack the program needs.
    stack: usize,
    source: String,
}

/// One step of the postfix program: push a value, or combine the top of the stack.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Instr {
    Num(f64),
    X,
    Y,
    Neg,
    Bin(Op),
    /// `a^b` with a constant exponent `b` (no `x` or `y` in it).
    PowConst,
    Func(Func),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Func {
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
    Sqrt,
    Abs,
}

/// A value with its first and second derivative along one direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet {
    /// Value.
    pub v: f64,
    /// First derivative.
    pub d1: f64,
    /// Second derivative.
    pub d2: f64,
}

impl Jet {
    fn constant(v: f64) -> Self {
        Self {
            v,
            d1: 0.0,
            d2: 0.0,
        }
    }
    /// Applies a scalar function with value `f`, derivative `g`, second derivative `h` at `self.v`.
    fn chain(self, f: f64, g: f64, h: f64) -> Self {
        Self {
            v: f,
            d1: g * self.d1,
            d2: h * self.d1 * self.d1 + g * self.d2,
        }
    }
    fn add(self, o: Self) -> Self {
        Self {
            v: self.v + o.v,
            d1: self.d1 + o.d1,
            d2: self.d2 + o.d2,
        }
    }
    fn sub(self, o: Self) -> Self {
        Self {
            v: self.v - o.v,
            d1: self.d1 - o.d1,
            d2: self.d2 - o.d2,
        }
    }
    fn mul(self, o: Self) -> Self {
        Self {
            v: self.v * o.v,
            d1: self.d1 * o.v + self.v * o.d1,
            d2: self.d2 * o.v + 2.0 * self.d1 * o.d1 + self.v * o.d2,
        }
    }
    fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(r, -r * r, 2.0 * r * r * r)
    }
    fn powc(self, c: f64) -> Self {
        let v = self.v;
        let (f, g, h) = if c == c.round() && c.abs() < 64.0 {
            let n = c as i32;
            (v.powi(n), c * v.powi(n - 1), c * (c - 1.0) * v.powi(n - 2))
        } else {
            (
                v.powf(c),
                c * v.powf(c - 1.0),
                c * (c - 1.0) * v.powf(c - 2.0),
            )
        };
        // powi(n - 2) with v = 0 gives inf * 0 below; the derivative terms then vanish
        let g = if self.d1 == 0.0 && self.d2 == 0.0 {
            0.0
        } else {
            g
        };
        let h = if self.d1 == 0.0 { 0.0 } else { h };
        self.chain(f, g, h)
    }
}

struct Parser<'a> {
    src: &'a [u8],
    pos: usize,
    /// The program so far.
    out: Vec<Instr>,
    /// Current nesting depth.
    depth: usize,
}

/// Whether a parsed part is free of `x` and `y`.
type Constant = bool;

impl Parser<'_> {
    fn err<T>(&self, message: impl Into<String>) -> Result<T> {
        Err(GeomError::Expression {
            column: self.pos + 1,
            message: message.into(),
        })
    }
    fn skip_ws(&mut self) {
        while self.pos < self.src.len() && self.src[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }
    fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.src.get(self.pos).copied()
    }
    fn eat(&mut self, c: u8) -> bool {
        if self.peek() == Some(c) {
            self.pos += 1;
            true
        } else {
            false
        }
    }
    /// Enters one level of nesting.
    fn enter(&mut self) -> Result<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return self.err(format!("nested deeper than {MAX_DEPTH} levels"));
        }
        Ok(())
    }
    fn expr(&mut self) -> Result<Constant> {
        let mut constant = self.term()?;
        loop {
            let op = match self.peek() {
                Some(b'+') => Op::Add,
                Some(b'-') => Op::Sub,
                _ => return Ok(constant),
            };
            self.pos += 1;
            constant &= self.term()?;
            self.out.push(Instr::Bin(op));
        }
    }
    fn term(&mut self) -> Result<Constant> {
        let mut constant = self.unary()?;
        loop {
            let op = match self.peek() {
                Some(b'*') => Op::Mul,
                Some(b'/') => Op::Div,
                _ => return Ok(constant),
            };
            self.pos += 1;
            constant &= self.unary()?;
            self.out.push(Instr::Bin(op));
        }
    }
    fn unary(&mut self) -> Result<Constant> {
        self.enter()?;
        // a run of signs, counted (not nested): `--x` is `-(-x)`
        let mut negations = 0usize;
        loop {
            if self.eat(b'-') {
                negations += 1;
            } else if !self.eat(b'+') {
                break;
            }
        }
        let constant = self.power()?;
        for _ in 0..negations {
            self.out.push(Instr::Neg);
        }
        self.depth -= 1;
        Ok(constant)
    }
    fn power(&mut self) -> Result<Constant> {
        let base = self.atom()?;
        if self.eat(b'^') {
            let exponent = self.unary()?;
            self.out.push(if exponent {
                Instr::PowConst
            } else {
                Instr::Bin(Op::Pow)
            });
            return Ok(base && exponent);
        }
        Ok(base)
    }
    fn atom(&mut self) -> Result<Constant> {
        match self.peek() {
            None => self.err("unexpected end of expression"),
            Some(b'(') => {
                self.pos += 1;
                self.enter()?;
                let e = self.expr()?;
                self.depth -= 1;
                if !self.eat(b')') {
                    return self.err("expected ')'");
                }
                Ok(e)
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => self.number(),
            Some(c) if c.is_ascii_alphabetic() => {
                let start = self.pos;
                while self.pos < self.src.len()
                    && (self.src[self.pos].is_ascii_alphanumeric() || self.src[self.pos] == b'_')
                {
                    self.pos += 1;
                }
                let name = std::str::from_utf8(&self.src[start..self.pos]).unwrap_or_default();
                let leaf = |p: &mut Self, i: Instr, constant: bool| {
                    p.out.push(i);
                    Ok(constant)
                };
                let func = match name {
                    "x" => return leaf(self, Instr::X, false),
                    "y" => return leaf(self, Instr::Y, false),
                    "pi" => return leaf(self, Instr::Num(std::f64::consts::PI), true),
                    "e" => return leaf(self, Instr::Num(std::f64::consts::E), true),
                    "sin" => Func::Sin,
                    "cos" => Func::Cos,
                    "tan" => Func::Tan,
                    "exp" => Func::Exp,
                    "ln" => Func::Ln,
                    "sqrt" => Func::Sqrt,
                    "abs" => Func::Abs,
                    _ => {
                        self.pos = start;
                        return self.err(format!(
                            "unknown name '{name}' (variables: x, y; constants: pi, e; functions: sin cos tan exp ln sqrt abs)"
                        ));
                    }
                };
                if !self.eat(b'(') {
                    return self.err(format!("expected '(' after {name}"));
                }
                self.enter()?;
                let constant = self.expr()?;
                self.depth -= 1;
                if !self.eat(b')') {
                    return self.err("expected ')'");
                }
                self.out.push(Instr::Func(func));
                Ok(constant)
            }
            Some(c) => self.err(format!("unexpected character '{}'", c as char)),
        }
    }
    fn number(&mut self) -> Result<Constant> {
        let start = self.pos;
        let s = self.src;
        let digits = |p: &mut usize| {
            while *p < s.len() && s[*p].is_ascii_digit() {
                *p += 1;
            }
        };
        digits(&mut self.pos);
        if self.pos < s.len() && s[self.pos] == b'.' {
            self.pos += 1;
            digits(&mut self.pos);
        }
        if self.pos < s.len() && (s[self.pos] == b'e' || s[self.pos] == b'E') {
            let save = self.pos;
            self.pos += 1;
            if self.pos < s.len() && (s[self.pos] == b'+' || s[self.pos] == b'-') {
                self.pos += 1;
            }
            let exp_start = self.pos;
            digits(&mut self.pos);
            if self.pos == exp_start {
                self.pos = save; // not an exponent: `2e` is 2 times e? keep it an error-free split
            }
        }
        let text = std::str::from_utf8(&s[start..self.pos]).unwrap_or_default();
        match text.parse::<f64>() {
            Ok(v) => {
                self.out.push(Instr::Num(v));
                Ok(true)
            }
            Err(_) => {
                self.pos = start;
                self.err(format!("malformed number '{text}'"))
            }
        }
    }
}

impl Expr {
    /// Parses an expression.
    ///
    /// # Errors
    /// [`GeomError::Expression`] with the 1-based column of the problem.
    ///
    /// # Example
    /// ```
    /// let f = geom::expr::Expr::parse("120*sin(x/300)*cos(y/500)").unwrap();
    /// assert!((f.eval(150.0 * std::f64::consts::PI, 0.0) - 120.0).abs() < 1e-12);
    /// ```
    pub fn parse(source: &str) -> Result<Self> {
        if source.len() > MAX_LENGTH {
            return Err(GeomError::Expression {
                column: MAX_LENGTH + 1,
                message: format!("longer than {MAX_LENGTH} bytes ({} bytes)", source.len()),
            });
        }
        let mut p = Parser {
            src: source.as_bytes(),
            pos: 0,
            out: Vec::new(),
            depth: 0,
        };
        p.expr()?;
        if p.peek().is_some() {
            return p.err("unexpected text after the expression");
        }
        let program = p.out;
        // the stack's height after each step
        let mut height = 0usize;
        let mut stack = 0usize;
        for i in &program {
            match i {
                Instr::Num(_) | Instr::X | Instr::Y => height += 1,
                Instr::Bin(_) | Instr::PowConst => height -= 1,
                Instr::Neg | Instr::Func(_) => {}
            }
            stack = stack.max(height);
        }
        Ok(Self {
            program,
            stack,
            source: source.to_string(),
        })
    }

    /// The source text.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// `f(x, y)`.
    pub fn eval(&self, x: f64, y: f64) -> f64 {
        self.run(Jet::constant(x), Jet::constant(y)).v
    }

    /// `f` along the line `(x0 + t·ux, y0 + t·uy)` at `t`: value, `df/dt`, `d²f/dt²`.
    pub fn eval_along(&self, (x0, y0): (f64, f64), (ux, uy): (f64, f64), t: f64) -> Jet {
        let x = Jet {
            v: x0 + t * ux,
            d1: ux,
            d2: 0.0,
        };
        let y = Jet {
            v: y0 + t * uy,
            d1: uy,
            d2: 0.0,
        };
        self.run(x, y)
    }

    /// Runs the program with `x` and `y`, on this thread's reused stack: an evaluation
    /// neither allocates nor clears memory (a cleared array per call cost a fifth of a
    /// height field's sectioning; `execute` writes every slot before it reads it).
    fn run(&self, x: Jet, y: Jet) -> Jet {
        thread_local! {
            static STACK: std::cell::RefCell<Vec<Jet>> = const { std::cell::RefCell::new(Vec::new()) };
        }
        STACK.with(|cell| match cell.try_borrow_mut() {
            Ok(mut buf) => {
                if buf.len() < self.stack {
                    buf.resize(self.stack, Jet::constant(0.0));
                }
                execute(&self.program, x, y, &mut buf[..self.stack])
            }
            // not reached (`execute` calls nothing that evaluates), but never a panic
            Err(_) => execute(
                &self.program,
                x,
                y,
                &mut vec![Jet::constant(0.0); self.stack],
            ),
        })
    }
}

/// Runs `program` on the stack `buf` (at least as deep as the program needs).
fn execute(program: &[Instr], x: Jet, y: Jet, buf: &mut [Jet]) -> Jet {
    let mut top = 0usize;
    for i in program {
        match *i {
            Instr::Num(v) => {
                buf[top] = Jet::constant(v);
                top += 1;
            }
            Instr::X => {
                buf[top] = x;
                top += 1;
            }
            Instr::Y => {
                buf[top] = y;
                top += 1;
            }
            Instr::Neg => {
                let a = buf[top - 1];
                buf[top - 1] = Jet {
                    v: -a.v,
                    d1: -a.d1,
                    d2: -a.d2,
                };
            }
            Instr::Bin(op) => {
                let (ja, jb) = (buf[top - 2], buf[top - 1]);
                top -= 1;
                buf[top - 1] = binary(op, ja, jb);
            }
            Instr::PowConst => {
                let (ja, jb) = (buf[top - 2], buf[top - 1]);
                top -= 1;
                buf[top - 1] = ja.powc(jb.v);
            }
            Instr::Func(f) => buf[top - 1] = func(f, buf[top - 1]),
        }
    }
    buf[0]
}

fn binary(op: Op, ja: Jet, jb: Jet) -> Jet {
    match op {
        Op::Add => ja.add(jb),
        Op::Sub => ja.sub(jb),
        Op::Mul => ja.mul(jb),
        Op::Div => ja.mul(jb.recip()),
        Op::Pow => {
            // a^b = exp(b ln a)
            let ln = ja.chain(ja.v.ln(), 1.0 / ja.v, -1.0 / (ja.v * ja.v));
            let e = jb.mul(ln);
            let ev = e.v.exp();
            e.chain(ev, ev, ev)
        }
    }
}

fn func(f: Func, a: Jet) -> Jet {
    let v = a.v;
    match f {
        Func::Sin => a.chain(v.sin(), v.cos(), -v.sin()),
        Func::Cos => a.chain(v.cos(), -v.sin(), -v.cos()),
        Func::Tan => {
            let t = v.tan();
            let s = 1.0 + t * t;
            a.chain(t, s, 2.0 * t * s)
        }
        Func::Exp => {
            let e = v.exp();
            a.chain(e, e, e)
        }
        Func::Ln => a.chain(v.ln(), 1.0 / v, -1.0 / (v * v)),
        Func::Sqrt => {
            let r = v.sqrt();
            a.chain(r, 0.5 / r, -0.25 / (r * v))
        }
        Func::Abs => {
            let s = if v < 0.0 { -1.0 } else { 1.0 };
            a.chain(v.abs(), s, 0.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn precedence_and_associativity() {
        let e = |s: &str| Expr::parse(s).unwrap().eval(2.0, 3.0);
        assert_eq!(e("1 + 2 * 3"), 7.0);
        assert_eq!(e("-2^2"), -4.0);
        assert_eq!(e("2^3^2"), 512.0);
        assert_eq!(e("2^-1"), 0.5);
        assert_eq!(e("(1 + 2) * 3"), 9.0);
        assert_eq!(e("x*y - y/x"), 6.0 - 1.5);
        assert_eq!(e("abs(-x)"), 2.0);
        assert!((e("sqrt(y*3)") - 3.0).abs() < 1e-15);
        assert!((e("ln(exp(x))") - 2.0).abs() < 1e-15);
        assert!((e("cos(pi)") + 1.0).abs() < 1e-15);
        assert_eq!(e("1.5e2"), 150.0);
        assert_eq!(e("--x"), 2.0);
        assert!((e("tan(0)")).abs() < 1e-15);
        assert!((e("sin(x)^2 + cos(x)^2") - 1.0).abs() < 1e-15);
    }

    #[test]
    fn errors_have_columns() {
        for (s, col) in [
            ("1 +", 4),
            ("sin x", 5),
            ("foo(1)", 1),
            ("(1", 3),
            ("1 2", 3),
            ("2 $ 3", 3),
            ("", 1),
        ] {
            match Expr::parse(s) {
                Err(GeomError::Expression { column, .. }) => assert_eq!(column, col, "{s}"),
                other => panic!("{s}: {other:?}"),
            }
        }
    }

    /// Deep nesting, long runs of signs and very long sums end in an error or a value, in
    /// linear time, without exhausting the stack (the hostile inputs of issue 18).
    #[test]
    fn hostile_expressions_end_quickly() {
        let deep = format!("{}x{}", "(".repeat(12_000), ")".repeat(12_000));
        assert!(Expr::parse(&deep).is_err());
        let signs = format!("{}x", "-".repeat(30_000));
        assert!(Expr::parse(&signs).is_err(), "longer than the limit");
        let signs = format!("{}x", "-".repeat(9_000));
        assert_eq!(Expr::parse(&signs).unwrap().eval(2.0, 0.0), 2.0);
        let sum = vec!["x"; 4_000].join("+");
        assert_eq!(Expr::parse(&sum).unwrap().eval(1.0, 0.0), 4000.0);
        let long = vec!["x"; 50_000].join("+");
        assert!(Expr::parse(&long).is_err());
        // constant exponents found in linear time: 1^1^…^1*x
        let pow = format!("{}*x", vec!["1"; 3_000].join("^"));
        let f = Expr::parse(&pow);
        assert!(
            f.is_err(),
            "3000 right-nested powers exceed the depth limit"
        );
        let pow = format!("{}*x", vec!["1"; 150].join("^"));
        assert_eq!(Expr::parse(&pow).unwrap().eval(3.0, 0.0), 3.0);
        let nested = format!(
            "{}x{}",
            "sin(".repeat(MAX_DEPTH / 2 - 1),
            ")".repeat(MAX_DEPTH / 2 - 1)
        );
        assert!(Expr::parse(&nested).is_ok());
    }

    #[test]
    fn derivatives_along_a_line_match_finite_differences() {
        let exprs = [
            "120*sin(x/300)*cos(y/500)",
            "0.3*cos(2*(pi/2 - y)^4)*sin(x)*exp(-0.1*x^2)",
            "sqrt(1 + x^2 + y^2) / (2 + tan(y/4)) - ln(3 + x*x)",
            "x^y + abs(x - 3)",
        ];
        let (o, u) = ((0.7, 0.4), (0.6, 0.8));
        for s in exprs {
            let f = Expr::parse(s).unwrap();
            for k in 0..20 {
                let t = 0.05 * k as f64;
                let j = f.eval_along(o, u, t);
                let g = |t: f64| f.eval_along(o, u, t).v;
                let h = 1e-4;
                let d1 = (g(t + h) - g(t - h)) / (2.0 * h);
                let d2 = (g(t + h) - 2.0 * g(t) + g(t - h)) / (h * h);
                assert!(
                    (j.d1 - d1).abs() < 1e-6 * (1.0 + d1.abs()),
                    "{s} t={t}: {} vs {d1}",
                    j.d1
                );
                assert!(
                    (j.d2 - d2).abs() < 1e-4 * (1.0 + d2.abs()),
                    "{s} t={t}: {} vs {d2}",
                    j.d2
                );
            }
        }
    }
}
