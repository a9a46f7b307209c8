//! The macro expression engine shared by every dialect: one AST, one evaluator, and a parser per
//! surface syntax (square brackets for Fanuc macro B, Haas, LinuxCNC and Dyna; round brackets and
//! R-parameters for Sinumerik).
//!
//! Values follow Fanuc macro B's null rules ([`Value`] is `None` for null, "vacant"): null acts as
//! 0 in arithmetic, is copied by a plain assignment, and is told apart from 0 only by `EQ`/`NE`.
//! Dialects without null (LinuxCNC, Sinumerik, Dyna) read an unset variable as 0; the reader
//! reports every variable read before it is set, in every dialect.

use std::fmt;

/// A value: `None` is Fanuc's null (`#0`, an unset variable).
pub type Value = Option<f64>;

/// A variable as written.
#[derive(Clone, Debug, PartialEq)]
pub enum VarRef {
    /// `#12`, `R3`: a numbered variable.
    Num(i64),
    /// `#[#1+2]`: a number computed at run time.
    Indirect(Box<Expr>),
    /// `#<name>` (LinuxCNC named parameter; `_` first is global).
    Named(String),
}

impl fmt::Display for VarRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VarRef::Num(n) => write!(f, "#{n}"),
            VarRef::Indirect(_) => write!(f, "#[…]"),
            VarRef::Named(s) => write!(f, "#<{s}>"),
        }
    }
}

/// A variable once its number is known: the key of the variable store.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum VarKey {
    /// A numbered variable (`#12`, `R3`).
    Num(i64),
    /// A named one, lower case (`#<_x>`).
    Named(String),
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `MOD` (LinuxCNC, Sinumerik; result has the sign of the divisor as in LinuxCNC)
    Mod,
    /// `**` (LinuxCNC)
    Pow,
    /// `EQ`, `==`
    Eq,
    /// `NE`, `<>`
    Ne,
    /// `GT`, `>`
    Gt,
    /// `GE`, `>=`
    Ge,
    /// `LT`, `<`
    Lt,
    /// `LE`, `<=`
    Le,
    /// Fanuc `AND`: bitwise on the integer values.
    BitAnd,
    /// Fanuc `OR`: bitwise.
    BitOr,
    /// Fanuc `XOR`: bitwise.
    BitXor,
    /// LinuxCNC and Sinumerik `AND`: logical.
    And,
    /// Logical `OR`.
    Or,
    /// Logical `XOR`.
    Xor,
}

/// Functions of one argument (two for `ATAN[y]/[x]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    /// Sine of degrees.
    Sin,
    /// Cosine of degrees.
    Cos,
    /// Tangent of degrees.
    Tan,
    /// Arc sine, degrees.
    Asin,
    /// Arc cosine, degrees.
    Acos,
    /// Arc tangent of one argument, degrees (−90 … 90).
    Atan,
    /// Fanuc `ATAN[y]/[x]`: 0 … 360 degrees (the Fanuc range, unsourced here: see docs/guide/verify-a-lathe-program.md, macro languages).
    Atan2Full,
    /// LinuxCNC `ATAN[y]/[x]`: −180 … 180 degrees.
    Atan2Signed,
    /// Square root (`SQRT`, Dyna `SQR`).
    Sqrt,
    /// Absolute value.
    Abs,
    /// Round half away from zero.
    Round,
    /// Toward zero (`FIX`, Sinumerik `TRUNC`).
    Fix,
    /// Away from zero (Fanuc `FUP`; LinuxCNC's FUP is the ceiling, see [`Func::Ceil`]).
    Fup,
    /// Ceiling (LinuxCNC `FUP`).
    Ceil,
    /// Floor (LinuxCNC `FIX`).
    Floor,
    /// Natural logarithm.
    Ln,
    /// eˣ.
    Exp,
    /// LinuxCNC `EXISTS[#<name>]`.
    Exists,
    /// Logical not (Sinumerik `NOT`).
    Not,
}

impl Func {
    /// The function's name as the dialects spell it.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "SIN",
            Func::Cos => "COS",
            Func::Tan => "TAN",
            Func::Asin => "ASIN",
            Func::Acos => "ACOS",
            Func::Atan | Func::Atan2Full | Func::Atan2Signed => "ATAN",
            Func::Sqrt => "SQRT",
            Func::Abs => "ABS",
            Func::Round => "ROUND",
            Func::Fix | Func::Floor => "FIX",
            Func::Fup | Func::Ceil => "FUP",
            Func::Ln => "LN",
            Func::Exp => "EXP",
            Func::Exists => "EXISTS",
            Func::Not => "NOT",
        }
    }
}

/// An expression.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// A literal.
    Num(f64),
    /// A variable.
    Var(VarRef),
    /// Unary minus.
    Neg(Box<Expr>),
    /// Operators of one precedence level applied left to right: `a + b - c` is the first operand
    /// and `[(+, b), (−, c)]`. Flat, so that a long sum is built, evaluated and dropped without
    /// recursing once per term.
    Chain(Box<Expr>, Vec<(BinOp, Expr)>),
    /// A function of its arguments.
    Call(Func, Vec<Expr>),
}

/// Where the evaluator reads variables.
/// How comparisons and MOD behave: LinuxCNC's interpreter compares EQ, NE, LE and GE with an
/// absolute tolerance of 1e-6 (`TOLERANCE_EQUAL`, from release 2.9.0 on; earlier builds compare
/// EQ and NE within 1e-4 and LE, GE exactly) and gives MOD the divisor's magnitude's sign
/// (never negative); the others compare within a relative 1e-9 and floor MOD.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Arithmetic {
    /// Relative 1e-9 for EQ/NE, exact LE/GE, MOD by floor division.
    #[default]
    Exact,
    /// LinuxCNC 2.9.0 and later: absolute 1e-6 for EQ/NE/LE/GE, MOD never negative.
    LinuxCnc,
    /// LinuxCNC before 2.9.0 (Debian 12's 2.9.0~pre1 package among them): absolute 1e-4 for
    /// EQ/NE, exact LE/GE, MOD never negative.
    LinuxCncBefore29,
}

pub trait Env {
    /// The comparison and MOD rules of the language.
    fn arithmetic(&self) -> Arithmetic {
        Arithmetic::Exact
    }
    /// The value of a variable (`None` for null or unset); the environment notes reads of unset
    /// variables itself.
    fn get(&mut self, key: &VarKey) -> Result<Value, String>;
    /// Whether a named variable exists (LinuxCNC `EXISTS`).
    fn exists(&mut self, key: &VarKey) -> bool;
    /// The value of a named variable; an environment of a few names (a target's `t` and `z`)
    /// answers without building a key.
    fn get_named(&mut self, name: &str) -> Result<Value, String> {
        self.get(&VarKey::Named(name.to_string()))
    }
}

/// Most nested levels of an expression (brackets, unary signs, function calls).
pub const MAX_EXPR_DEPTH: usize = 64;

fn truthy(v: f64) -> bool {
    v != 0.0
}

fn bits(v: f64, what: &str) -> Result<i64, String> {
    let r = v.round();
    if (v - r).abs() > 1e-9 || r.abs() > 9.0e15 {
        return Err(format!("{what} takes whole numbers, not {v}"));
    }
    Ok(r as i64)
}

/// Resolves a variable reference to its key.
pub fn key_of(v: &VarRef, env: &mut dyn Env) -> Result<VarKey, String> {
    match v {
        VarRef::Num(n) => Ok(VarKey::Num(*n)),
        VarRef::Named(s) => Ok(VarKey::Named(s.clone())),
        VarRef::Indirect(e) => {
            let n = eval(e, env, 0)?.unwrap_or(0.0);
            let r = n.round();
            if (n - r).abs() > 1e-6 || !(0.0..=1.0e6).contains(&r) {
                return Err(format!("#[{n}] is not a variable number"));
            }
            Ok(VarKey::Num(r as i64))
        }
    }
}

/// π as x87 extended precision holds it (`M_PIl`): a 64-bit mantissa, value `PI_X87 · 2^-62`.
const PI_X87: u64 = 0xC90F_DAA2_2168_C235;

/// A positive value `m · 2^e` rounded to `bits` significant bits, half to even; `sticky` says
/// that something nonzero lies below `m`.
fn round_to(m: u128, e: i32, bits: u32, sticky: bool) -> (u128, i32) {
    let len = 128 - m.leading_zeros();
    if len <= bits {
        return (m, e);
    }
    let shift = len - bits;
    let q = m >> shift;
    let rest = m & ((1u128 << shift) - 1);
    let half = 1u128 << (shift - 1);
    let up = rest > half || (rest == half && (sticky || q & 1 == 1));
    let q = q + u128::from(up);
    // A carry out of the top bit renormalises.
    if 128 - q.leading_zeros() > bits {
        (q >> 1, e + shift as i32 + 1)
    } else {
        (q, e + shift as i32)
    }
}

/// `num · 2^e / den` as a quotient of at least 66 bits, its exponent, and whether a remainder
/// is left (the sticky bit of the rounding after it).
fn div_ext(num: u128, den: u128, e: i32) -> (u128, i32, bool) {
    let (mut q, mut r, mut e) = (num / den, num % den, e);
    while 128 - q.leading_zeros() < 66 {
        // One more bit of the quotient, by long division.
        r <<= 1;
        q = (q << 1) | u128::from(r >= den);
        if r >= den {
            r -= den;
        }
        e -= 1;
    }
    (q, e, r != 0)
}

/// `x` as a positive mantissa and exponent (`|x| = m · 2^e`), for normal numbers.
fn split(x: f64) -> (u128, i32) {
    let bits = x.abs().to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    (u128::from((bits & ((1u64 << 52) - 1)) | (1u64 << 52)), exp - 1075)
}

/// `m · 2^e` (m below 2^53) as a double.
fn join(negative: bool, m: u128, e: i32) -> f64 {
    let v = (m as f64) * 2f64.powi(e);
    if negative {
        -v
    } else {
        v
    }
}

/// Whether `x` is a normal number whose conversion stays far from overflow and underflow.
fn plain(x: f64) -> bool {
    x.is_normal() && (1e-280..1e280).contains(&x.abs())
}

/// Degrees to radians as LinuxCNC computes them, `(x · M_PIl) / 180.0` in x87 long double,
/// rounded to 64 bits after each step and to a double at the end; `to_radians` rounds
/// differently, and an ulp off is a jump after MOD.
fn deg_to_rad(x: f64) -> f64 {
    if !plain(x) {
        return x.to_radians();
    }
    let (m, e) = split(x);
    let (p, pe) = round_to(m * u128::from(PI_X87), e - 62, 64, false);
    let (q, qe, sticky) = div_ext(p << 64, 180, pe - 64);
    let (q, qe) = round_to(q, qe, 64, sticky);
    let (d, de) = round_to(q, qe, 53, false);
    join(x < 0.0, d, de)
}

/// Radians to degrees as LinuxCNC computes them, `(a · 180.0) / M_PIl`: the product in double,
/// the quotient in long double.
fn rad_to_deg(a: f64) -> f64 {
    if !plain(a) {
        return a.to_degrees();
    }
    // a · 180.0 is a product of two doubles: rounded to a double first.
    let (p, e) = split(a * 180.0);
    let shift = p.leading_zeros() - 64;
    let (p, pe) = (p << shift, e - shift as i32);
    let (q, qe, sticky) = div_ext(p << 64, u128::from(PI_X87), pe - 64 + 62);
    let (q, qe) = round_to(q, qe, 64, sticky);
    let (d, de) = round_to(q, qe, 53, false);
    join(a < 0.0, d, de)
}

/// One binary operator on two values: EQ and NE tell null from 0 (Fanuc), the other operators
/// read null as 0.
fn apply(op: BinOp, x: Value, y: Value, arith: Arithmetic) -> Result<f64, String> {
    // LinuxCNC: two numbers within 1e-6 are equal (its TOLERANCE_EQUAL), for EQ, NE, LE, GE;
    // before 2.9.0 within 1e-4, for EQ and NE only.
    let near = |x: f64, y: f64| (x - y).abs() < 1e-6;
    let near_before_29 = |x: f64, y: f64| (x - y).abs() < 1e-4;
    if matches!(op, BinOp::Eq | BinOp::Ne) {
        let eq = match (x, y) {
            (None, None) => true,
            (Some(x), Some(y)) => match arith {
                Arithmetic::Exact => (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1.0),
                Arithmetic::LinuxCnc => near(x, y),
                Arithmetic::LinuxCncBefore29 => near_before_29(x, y),
            },
            _ => false,
        };
        return Ok(if eq == (op == BinOp::Eq) { 1.0 } else { 0.0 });
    }
    let (x, y) = (x.unwrap_or(0.0), y.unwrap_or(0.0));
    let b2 = |c: bool| if c { 1.0 } else { 0.0 };
    let lc = arith == Arithmetic::LinuxCnc;
    Ok(match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div => {
            if y == 0.0 {
                return Err("division by zero".into());
            }
            x / y
        }
        BinOp::Mod => {
            if y == 0.0 {
                return Err("MOD by zero".into());
            }
            match arith {
                Arithmetic::Exact => x - y * (x / y).floor(),
                // fmod, then the divisor's magnitude added to a negative result.
                Arithmetic::LinuxCnc | Arithmetic::LinuxCncBefore29 => {
                    let r = x % y;
                    if r < 0.0 {
                        r + y.abs()
                    } else {
                        r
                    }
                }
            }
        }
        BinOp::Pow => x.powf(y),
        BinOp::Eq | BinOp::Ne => unreachable!("handled above"),
        BinOp::Gt => b2(x > y),
        BinOp::Ge => b2(x >= y || (lc && near(x, y))),
        BinOp::Lt => b2(x < y),
        BinOp::Le => b2(x <= y || (lc && near(x, y))),
        BinOp::BitAnd => (bits(x, "AND")? & bits(y, "AND")?) as f64,
        BinOp::BitOr => (bits(x, "OR")? | bits(y, "OR")?) as f64,
        BinOp::BitXor => (bits(x, "XOR")? ^ bits(y, "XOR")?) as f64,
        BinOp::And => b2(truthy(x) && truthy(y)),
        BinOp::Or => b2(truthy(x) || truthy(y)),
        BinOp::Xor => b2(truthy(x) != truthy(y)),
    })
}

/// Evaluates an expression; null propagates through a bare variable only.
pub fn eval(e: &Expr, env: &mut dyn Env, depth: usize) -> Result<Value, String> {
    if depth > MAX_EXPR_DEPTH {
        return Err("the expression nests too deeply".into());
    }
    let num =
        |e: &Expr, env: &mut dyn Env| -> Result<f64, String> { Ok(eval(e, env, depth + 1)?.unwrap_or(0.0)) };
    let v = match e {
        Expr::Num(v) => *v,
        Expr::Var(VarRef::Named(name)) => return env.get_named(name),
        Expr::Var(r) => {
            let k = key_of(r, env)?;
            return env.get(&k);
        }
        Expr::Neg(a) => -num(a, env)?,
        Expr::Chain(first, rest) => {
            let mut acc = eval(first, env, depth + 1)?;
            for (op, e) in rest {
                let y = eval(e, env, depth + 1)?;
                acc = Some(apply(*op, acc, y, env.arithmetic())?);
            }
            return Ok(acc);
        }
        Expr::Call(f, args) => {
            if *f == Func::Exists {
                let Some(Expr::Var(r)) = args.first() else {
                    return Err("EXISTS takes a named parameter".into());
                };
                let k = key_of(r, env)?;
                return Ok(Some(if env.exists(&k) { 1.0 } else { 0.0 }));
            }
            let a = num(&args[0], env)?;
            let b = match f {
                Func::Atan2Full | Func::Atan2Signed => Some(num(&args[1], env)?),
                _ => None,
            };
            call_fn(*f, a, b, env.arithmetic())?
        }
    };
    if !v.is_finite() {
        return Err("the expression is not a finite number".into());
    }
    Ok(Some(v))
}

/// A function of one argument (`b`, the second, for the two-argument arc tangents) as the
/// evaluator computes it: degrees as LinuxCNC converts them (x87 long double, emulated) under
/// its arithmetic, elsewhere as Rust does (the controls' own rounding is not published).
fn call_fn(f: Func, a: f64, b: Option<f64>, arith: Arithmetic) -> Result<f64, String> {
    let x87 = match arith {
        Arithmetic::LinuxCnc | Arithmetic::LinuxCncBefore29 => true,
        Arithmetic::Exact => false,
    };
    let deg_to_rad = |a: f64| if x87 { deg_to_rad(a) } else { a.to_radians() };
    let rad_to_deg = |a: f64| if x87 { rad_to_deg(a) } else { a.to_degrees() };
    Ok(match f {
        Func::Sin => deg_to_rad(a).sin(),
        Func::Cos => deg_to_rad(a).cos(),
        Func::Tan => deg_to_rad(a).tan(),
        Func::Asin => {
            if !(-1.0..=1.0).contains(&a) {
                return Err(format!("ASIN of {a}: outside −1 … 1"));
            }
            rad_to_deg(a.asin())
        }
        Func::Acos => {
            if !(-1.0..=1.0).contains(&a) {
                return Err(format!("ACOS of {a}: outside −1 … 1"));
            }
            rad_to_deg(a.acos())
        }
        Func::Atan => rad_to_deg(a.atan()),
        Func::Atan2Full | Func::Atan2Signed => {
            let x = b.unwrap_or(0.0);
            let d = rad_to_deg(a.atan2(x));
            if f == Func::Atan2Full && d < 0.0 {
                d + 360.0
            } else {
                d
            }
        }
        Func::Sqrt => {
            if a < 0.0 {
                return Err(format!("square root of {a}"));
            }
            a.sqrt()
        }
        Func::Abs => a.abs(),
        Func::Round => a.round(),
        Func::Fix => a.trunc(),
        Func::Fup => {
            if a >= 0.0 {
                a.ceil()
            } else {
                a.floor()
            }
        }
        Func::Ceil => a.ceil(),
        Func::Floor => a.floor(),
        Func::Ln => {
            if a <= 0.0 {
                return Err(format!("LN of {a}"));
            }
            a.ln()
        }
        Func::Exp => a.exp(),
        Func::Not => b2n(!truthy(a)),
        Func::Exists => return Err("EXISTS takes a named parameter".into()),
    })
}

/// One step of a [`Compiled`] expression, on a stack of numbers.
#[derive(Clone, Debug)]
enum Op {
    Num(f64),
    /// The value of the name at this index of the names compiled for.
    Name(usize),
    /// A variable read from the environment ([`Compiled::for_env`]).
    Var(VarKey),
    Neg,
    Bin(BinOp),
    Call(Func, bool),
}

/// An expression over a few named numbers (a target formula's t and z) turned into a flat list
/// of steps: what [`eval`] computes for it, without walking the tree or asking an [`Env`]. Any
/// step [`eval`] would refuse (a division by zero, a root of a negative, a value not finite)
/// makes [`Compiled::run`] answer `None`, for [`eval`] to give its error.
#[derive(Clone, Debug)]
pub(crate) struct Compiled {
    ops: Vec<Op>,
    arith: Arithmetic,
}

/// Most numbers a [`Compiled`] expression holds at once: deeper ones are not compiled.
const COMPILED_STACK: usize = 32;

impl Compiled {
    /// `e` compiled for the named numbers `names` (in that order, as [`Compiled::run`] takes
    /// them); `None` when it reads anything else (`#` variables, other names, EXISTS) or nests
    /// deeper than the evaluator allows.
    pub(crate) fn new(e: &Expr, names: &[&str], arith: Arithmetic) -> Option<Compiled> {
        Compiled::build(e, Some(names), arith)
    }

    /// `e` compiled to read its variables (`#1`, `#<name>`, named words) from an [`Env`] when
    /// run ([`Compiled::run_in`]); `None` for an indirect variable (`#[#1]`), EXISTS, or a nesting
    /// deeper than the evaluator allows.
    pub(crate) fn for_env(e: &Expr, arith: Arithmetic) -> Option<Compiled> {
        Compiled::build(e, None, arith)
    }

    fn build(e: &Expr, names: Option<&[&str]>, arith: Arithmetic) -> Option<Compiled> {
        /// Emits the steps of `e`, which leave one number on a stack already `height` high.
        fn emit(
            e: &Expr,
            names: Option<&[&str]>,
            ops: &mut Vec<Op>,
            depth: usize,
            height: usize,
        ) -> Option<()> {
            if depth > MAX_EXPR_DEPTH || height >= COMPILED_STACK {
                return None;
            }
            match e {
                Expr::Num(v) => ops.push(Op::Num(*v)),
                Expr::Var(VarRef::Named(n)) => match names {
                    Some(names) => ops.push(Op::Name(names.iter().position(|m| m == n)?)),
                    None => ops.push(Op::Var(VarKey::Named(n.clone()))),
                },
                Expr::Var(VarRef::Num(n)) if names.is_none() => ops.push(Op::Var(VarKey::Num(*n))),
                Expr::Var(_) | Expr::Call(Func::Exists, _) => return None,
                Expr::Neg(a) => {
                    emit(a, names, ops, depth + 1, height)?;
                    ops.push(Op::Neg);
                }
                Expr::Chain(first, rest) => {
                    emit(first, names, ops, depth + 1, height)?;
                    for (op, e) in rest {
                        emit(e, names, ops, depth + 1, height + 1)?;
                        ops.push(Op::Bin(*op));
                    }
                }
                Expr::Call(f, args) => {
                    let two = matches!(f, Func::Atan2Full | Func::Atan2Signed);
                    emit(args.first()?, names, ops, depth + 1, height)?;
                    if two {
                        emit(args.get(1)?, names, ops, depth + 1, height + 1)?;
                    }
                    ops.push(Op::Call(*f, two));
                }
            }
            Some(())
        }
        let mut ops = Vec::new();
        emit(e, names, &mut ops, 0, 0)?;
        Some(Compiled { ops, arith })
    }

    /// What [`eval`] gives for the expression compiled by [`Compiled::for_env`], its variables
    /// read from `env` (null as the evaluator has it: a bare variable's null is the value, an
    /// operand's reads as 0; a chain's result is not checked for finiteness, every other
    /// step's is); `None` where [`eval`] would give an error.
    pub(crate) fn run_in(&self, env: &mut dyn Env) -> Option<Value> {
        let mut stack = [None; COMPILED_STACK];
        let mut sp = 0usize;
        for op in &self.ops {
            let v: Value = match op {
                Op::Num(v) => Some(*v),
                Op::Name(_) => return None,
                Op::Var(k) => env.get(k).ok()?,
                Op::Neg => {
                    sp -= 1;
                    Some(-stack[sp].unwrap_or(0.0))
                }
                Op::Bin(b) => {
                    sp -= 2;
                    let v = apply(*b, stack[sp], stack[sp + 1], self.arith).ok()?;
                    stack[sp] = Some(v);
                    sp += 1;
                    continue;
                }
                Op::Call(f, two) => {
                    let (a, b) = if *two {
                        sp -= 2;
                        (stack[sp].unwrap_or(0.0), Some(stack[sp + 1].unwrap_or(0.0)))
                    } else {
                        sp -= 1;
                        (stack[sp].unwrap_or(0.0), None)
                    };
                    Some(call_fn(*f, a, b, self.arith).ok()?)
                }
            };
            if !matches!(op, Op::Var(_)) && !v.is_some_and(f64::is_finite) {
                return None;
            }
            stack[sp] = v;
            sp += 1;
        }
        debug_assert_eq!(sp, 1, "a compiled expression leaves one number");
        if sp == 1 {
            Some(stack[0])
        } else {
            None
        }
    }

    /// The value for the named numbers `values` (in the order compiled for); `None` where
    /// [`eval`] would give an error.
    pub(crate) fn run(&self, values: &[f64]) -> Option<f64> {
        let mut stack = [0.0f64; COMPILED_STACK];
        let mut sp = 0usize;
        for op in &self.ops {
            let v = match *op {
                Op::Num(v) => v,
                Op::Name(i) => *values.get(i)?,
                Op::Var(_) => return None,
                Op::Neg => {
                    sp -= 1;
                    -stack[sp]
                }
                Op::Bin(b) => {
                    sp -= 2;
                    apply(b, Some(stack[sp]), Some(stack[sp + 1]), self.arith).ok()?
                }
                Op::Call(f, two) => {
                    let (a, b) = if two {
                        sp -= 2;
                        (stack[sp], Some(stack[sp + 1]))
                    } else {
                        sp -= 1;
                        (stack[sp], None)
                    };
                    call_fn(f, a, b, self.arith).ok()?
                }
            };
            if !v.is_finite() {
                return None;
            }
            stack[sp] = v;
            sp += 1;
        }
        debug_assert_eq!(sp, 1, "a compiled expression leaves one number");
        (sp == 1).then_some(stack[0])
    }
}

fn b2n(c: bool) -> f64 {
    if c {
        1.0
    } else {
        0.0
    }
}

/// The bracket syntaxes: which operators and functions, at which precedence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Syntax {
    /// Fanuc custom macro B (and Haas): `* / AND MOD` above `+ - OR XOR` above the relations;
    /// AND OR XOR bitwise; `ATAN[y]/[x]` 0 … 360°; `#0` is null.
    MacroB,
    /// LinuxCNC: `**` above `* / MOD` above `+ -` above the relations above `AND OR XOR`
    /// (logical); named parameters.
    LinuxCnc,
    /// Dyna DM2900: Fanuc's operators, functions without brackets (`COS#14`, `SQR #13`).
    Dyna,
    /// Sinumerik: round brackets, R-parameters, `== <> > >= < <=`, `AND OR XOR NOT`.
    Sinumerik,
    /// Formulas of target files: round brackets, named variables as bare words (`t`, `z`), `PI`,
    /// `^` and `**` for powers, functions `sin(…)` … `atan2(y, x)` in degrees as the macros have
    /// them.
    Formula,
    /// Heidenhain Klartext Q-parameter formulas: round brackets, `Q12` variables, `+ - * / ^`,
    /// `PI`, functions `SIN(…)` … `SQRT(…)` in degrees.
    Klartext,
}

/// A parse error: the 0-based character offset in the parsed text, and what is wrong.
pub type ParseError = (usize, String);

/// A parser over a whitespace-free (bracket syntaxes) or spaced (Sinumerik) upper-case text.
pub struct Parser<'a> {
    c: &'a [char],
    /// Current offset.
    pub i: usize,
    syntax: Syntax,
    depth: usize,
}

impl<'a> Parser<'a> {
    /// A parser at offset `i` of `c`.
    pub fn new(c: &'a [char], i: usize, syntax: Syntax) -> Parser<'a> {
        Parser { c, i, syntax, depth: 0 }
    }

    fn peek(&self) -> Option<char> {
        self.c.get(self.i).copied()
    }

    fn skip_ws(&mut self) {
        if matches!(self.syntax, Syntax::Sinumerik | Syntax::Formula | Syntax::Klartext) {
            while matches!(self.peek(), Some(' ' | '\t')) {
                self.i += 1;
            }
        }
    }

    fn err<T>(&self, m: impl Into<String>) -> Result<T, ParseError> {
        Err((self.i, m.into()))
    }

    fn letters_at(&self, i: usize) -> String {
        let mut j = i;
        while j < self.c.len() && (self.c[j].is_ascii_alphabetic() || (j > i && self.c[j] == '_')) {
            j += 1;
        }
        self.c[i..j].iter().collect::<String>().to_ascii_uppercase()
    }

    fn binop(&mut self, level: u8) -> Option<BinOp> {
        self.skip_ws();
        let i = self.i;
        let c = self.peek()?;
        let two: String = self.c[i..(i + 2).min(self.c.len())].iter().collect();
        let sym = |s: &str| -> Option<(BinOp, usize)> {
            Some(match s {
                "+" => (BinOp::Add, 1),
                "-" => (BinOp::Sub, 1),
                "*" => (BinOp::Mul, 1),
                "/" => (BinOp::Div, 1),
                _ => return None,
            })
        };
        let (op, len) = if self.syntax == Syntax::Sinumerik && matches!(c, '=' | '<' | '>') {
            match two.as_str() {
                "==" => (BinOp::Eq, 2),
                "<>" => (BinOp::Ne, 2),
                ">=" => (BinOp::Ge, 2),
                "<=" => (BinOp::Le, 2),
                _ if c == '>' => (BinOp::Gt, 1),
                _ if c == '<' => (BinOp::Lt, 1),
                _ => return None,
            }
        } else if two == "**" && matches!(self.syntax, Syntax::LinuxCnc | Syntax::Formula) {
            (BinOp::Pow, 2)
        } else if c == '^' && matches!(self.syntax, Syntax::Formula | Syntax::Klartext) {
            (BinOp::Pow, 1)
        } else if c.is_ascii_alphabetic() && matches!(self.syntax, Syntax::Formula | Syntax::Klartext) {
            // Formulas have no word operators: a word there is a name, not an operator.
            return None;
        } else if c.is_ascii_alphabetic() {
            let mut w = self.letters_at(i);
            // Where spaces mean nothing (all but Sinumerik), an operator runs straight into the
            // word after it: `1 EQ ACOS[1]` reads as `1EQACOS[1]`, and the operator is the
            // letters it starts with (LinuxCNC's read_operation).
            if self.syntax != Syntax::Sinumerik {
                const WORD_OPS: [&str; 10] = ["MOD", "AND", "XOR", "OR", "EQ", "NE", "GT", "GE", "LT", "LE"];
                if let Some(op) = WORD_OPS.iter().find(|o| w.starts_with(**o)) {
                    w = (*op).to_string();
                }
            }
            let bitwise = matches!(self.syntax, Syntax::MacroB | Syntax::Dyna);
            let op = match w.as_str() {
                "EQ" if self.syntax != Syntax::Sinumerik => BinOp::Eq,
                "NE" if self.syntax != Syntax::Sinumerik => BinOp::Ne,
                "GT" if self.syntax != Syntax::Sinumerik => BinOp::Gt,
                "GE" if self.syntax != Syntax::Sinumerik => BinOp::Ge,
                "LT" if self.syntax != Syntax::Sinumerik => BinOp::Lt,
                "LE" if self.syntax != Syntax::Sinumerik => BinOp::Le,
                "AND" if bitwise => BinOp::BitAnd,
                "OR" if bitwise => BinOp::BitOr,
                "XOR" if bitwise => BinOp::BitXor,
                "AND" => BinOp::And,
                "OR" => BinOp::Or,
                "XOR" => BinOp::Xor,
                "MOD" => BinOp::Mod,
                _ => return None,
            };
            (op, w.len())
        } else {
            sym(&c.to_string())?
        };
        if self.level(op) != level {
            return None;
        }
        self.i += len;
        Some(op)
    }

    /// Precedence level, 0 lowest.
    fn level(&self, op: BinOp) -> u8 {
        use BinOp::*;
        match self.syntax {
            Syntax::MacroB | Syntax::Dyna => match op {
                Eq | Ne | Gt | Ge | Lt | Le => 0,
                Add | Sub | BitOr | BitXor | Or | Xor => 1,
                Mul | Div | Mod | BitAnd | And => 2,
                Pow => 3,
            },
            Syntax::LinuxCnc | Syntax::Sinumerik | Syntax::Formula | Syntax::Klartext => match op {
                And | Or | Xor | BitAnd | BitOr | BitXor => 0,
                Eq | Ne | Gt | Ge | Lt | Le => 1,
                Add | Sub => 2,
                Mul | Div | Mod => 3,
                Pow => 4,
            },
        }
    }

    fn top(&self) -> u8 {
        match self.syntax {
            Syntax::MacroB | Syntax::Dyna => 3,
            Syntax::LinuxCnc | Syntax::Sinumerik | Syntax::Formula | Syntax::Klartext => 4,
        }
    }

    /// A whole expression.
    pub fn expr(&mut self) -> Result<Expr, ParseError> {
        self.binary(0)
    }

    fn binary(&mut self, level: u8) -> Result<Expr, ParseError> {
        if level > self.top() {
            return self.unary();
        }
        let lhs = self.binary(level + 1)?;
        let mut rest = Vec::new();
        while let Some(op) = self.binop(level) {
            rest.push((op, self.binary(level + 1)?));
        }
        Ok(if rest.is_empty() { lhs } else { Expr::Chain(Box::new(lhs), rest) })
    }

    fn open(&self) -> char {
        if matches!(self.syntax, Syntax::Sinumerik | Syntax::Formula | Syntax::Klartext) {
            '('
        } else {
            '['
        }
    }

    fn close(&self) -> char {
        if matches!(self.syntax, Syntax::Sinumerik | Syntax::Formula | Syntax::Klartext) {
            ')'
        } else {
            ']'
        }
    }

    /// A signed operand: what an address may take (`-#1`, `[…]`, `12.5`, `#[…]`).
    pub fn unary(&mut self) -> Result<Expr, ParseError> {
        self.depth += 1;
        if self.depth > MAX_EXPR_DEPTH {
            return self.err("the expression nests too deeply");
        }
        self.skip_ws();
        let r = match self.peek() {
            Some('-') => {
                self.i += 1;
                self.unary().map(|e| Expr::Neg(Box::new(e)))
            }
            Some('+') => {
                self.i += 1;
                self.unary()
            }
            _ => self.primary(),
        };
        self.depth -= 1;
        r
    }

    fn group(&mut self) -> Result<Expr, ParseError> {
        // At the opening bracket.
        self.i += 1;
        let e = self.expr()?;
        self.skip_ws();
        if self.peek() != Some(self.close()) {
            return self.err(format!("'{}' missing", self.close()));
        }
        self.i += 1;
        Ok(e)
    }

    fn number(&mut self) -> Result<Expr, ParseError> {
        let s = self.i;
        let mut point = false;
        while let Some(c) = self.peek() {
            if c.is_ascii_digit() || (c == '.' && !point) {
                point |= c == '.';
                self.i += 1;
            } else {
                break;
            }
        }
        let t: String = self.c[s..self.i].iter().collect();
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Expr::Num(v)),
            _ => Err((s, format!("'{t}' is not a number"))),
        }
    }

    fn primary(&mut self) -> Result<Expr, ParseError> {
        let Some(c) = self.peek() else { return self.err("the expression ends too early") };
        if c == self.open() {
            return self.group();
        }
        if c.is_ascii_digit() || c == '.' {
            return self.number();
        }
        if c == '#' && !matches!(self.syntax, Syntax::Sinumerik | Syntax::Formula | Syntax::Klartext) {
            return self.var().map(Expr::Var);
        }
        if c.is_ascii_alphabetic() {
            let start = self.i;
            let name = self.letters_at(self.i);
            if self.syntax == Syntax::Klartext && name == "PI" {
                self.i += 2;
                return Ok(Expr::Num(std::f64::consts::PI));
            }
            // Sinumerik R-parameters: R3, R[…] is not read; Klartext's Q-parameters: Q12.
            if (self.syntax == Syntax::Sinumerik && name == "R")
                || (self.syntax == Syntax::Klartext && name == "Q")
            {
                self.i += 1;
                let ds = self.i;
                while matches!(self.peek(), Some(d) if d.is_ascii_digit()) {
                    self.i += 1;
                }
                let t: String = self.c[ds..self.i].iter().collect();
                return t
                    .parse::<i64>()
                    .map(|n| Expr::Var(VarRef::Num(n)))
                    .map_err(|_| (start, format!("{name} needs a parameter number")));
            }
            if self.syntax == Syntax::Formula {
                // A word not followed by '(' is a name (`t`, `z`) or the constant PI.
                let mut j = self.i + name.len();
                while matches!(self.c.get(j), Some(' ' | '\t')) {
                    j += 1;
                }
                if self.c.get(j) != Some(&'(') {
                    self.i += name.len();
                    return Ok(if name == "PI" {
                        Expr::Num(std::f64::consts::PI)
                    } else {
                        Expr::Var(VarRef::Named(name.to_ascii_lowercase()))
                    });
                }
            }
            let f = match (name.as_str(), self.syntax) {
                ("SIN", _) => Func::Sin,
                ("COS", _) => Func::Cos,
                ("TAN", _) => Func::Tan,
                ("ASIN", _) => Func::Asin,
                ("ACOS", _) => Func::Acos,
                ("ATAN", Syntax::Sinumerik) => Func::Atan,
                ("ATAN", _) => Func::Atan,
                ("ATAN2", Syntax::Sinumerik | Syntax::Formula) => Func::Atan2Signed,
                ("SQRT", _) => Func::Sqrt,
                ("SQR", Syntax::Dyna) => Func::Sqrt,
                ("ABS", _) => Func::Abs,
                ("ROUND", _) => Func::Round,
                ("FIX", Syntax::LinuxCnc) => Func::Floor,
                ("FUP", Syntax::LinuxCnc) => Func::Ceil,
                ("FIX", _) | ("TRUNC", Syntax::Sinumerik) | ("INT", Syntax::Klartext) => Func::Fix,
                ("FUP", _) => Func::Fup,
                ("LN", _) => Func::Ln,
                ("EXP", _) => Func::Exp,
                ("EXISTS", Syntax::LinuxCnc) => Func::Exists,
                ("NOT", Syntax::Sinumerik) => Func::Not,
                ("TRUE", Syntax::Sinumerik) => {
                    self.i += 4;
                    return Ok(Expr::Num(1.0));
                }
                ("FALSE", Syntax::Sinumerik) => {
                    self.i += 5;
                    return Ok(Expr::Num(0.0));
                }
                _ => return Err((start, format!("unknown function or name {name}"))),
            };
            self.i += name.len();
            if f == Func::Atan && self.syntax != Syntax::Sinumerik {
                // ATAN[y]/[x]: the two-argument form.
                self.skip_ws();
                if self.peek() == Some(self.open()) {
                    let y = self.group()?;
                    if self.peek() == Some('/') && self.c.get(self.i + 1) == Some(&self.open()) {
                        self.i += 1;
                        let x = self.group()?;
                        let f2 =
                            if self.syntax == Syntax::LinuxCnc { Func::Atan2Signed } else { Func::Atan2Full };
                        return Ok(Expr::Call(f2, vec![y, x]));
                    }
                    return Ok(Expr::Call(Func::Atan, vec![y]));
                }
            }
            if f == Func::Atan2Signed
                && matches!(self.syntax, Syntax::Sinumerik | Syntax::Formula | Syntax::Klartext)
            {
                return self.args2(f);
            }
            self.skip_ws();
            let arg = if self.peek() == Some(self.open()) {
                self.group()?
            } else if self.syntax == Syntax::Dyna || self.syntax == Syntax::Sinumerik && f == Func::Not {
                // Dyna writes functions without brackets: COS#14, SQR #13.
                self.unary()?
            } else {
                return Err((
                    self.i,
                    format!("{} needs its argument in {}{}", f.name(), self.open(), self.close()),
                ));
            };
            return Ok(Expr::Call(f, vec![arg]));
        }
        self.err(format!("unexpected '{c}' in an expression"))
    }

    fn args2(&mut self, f: Func) -> Result<Expr, ParseError> {
        self.skip_ws();
        if self.peek() != Some('(') {
            return self.err(format!("{} needs ( )", f.name()));
        }
        self.i += 1;
        let a = self.expr()?;
        self.skip_ws();
        if self.peek() != Some(',') {
            return self.err("',' expected");
        }
        self.i += 1;
        let b = self.expr()?;
        self.skip_ws();
        if self.peek() != Some(')') {
            return self.err("')' missing");
        }
        self.i += 1;
        Ok(Expr::Call(f, vec![a, b]))
    }

    /// A variable at `#`: `#12`, `#[expr]`, `#<name>`.
    pub fn var(&mut self) -> Result<VarRef, ParseError> {
        let start = self.i;
        self.i += 1;
        match self.peek() {
            Some('[') => {
                let e = self.group()?;
                Ok(VarRef::Indirect(Box::new(e)))
            }
            Some('<') if self.syntax == Syntax::LinuxCnc => {
                let close = self.c[self.i..]
                    .iter()
                    .position(|&c| c == '>')
                    .ok_or((start, "named parameter #<… has no closing '>'".to_string()))?;
                let name: String =
                    self.c[self.i + 1..self.i + close].iter().collect::<String>().to_ascii_lowercase();
                if name.is_empty() {
                    return Err((start, "empty parameter name #<>".into()));
                }
                self.i += close + 1;
                Ok(VarRef::Named(name))
            }
            Some(d) if d.is_ascii_digit() => {
                let ds = self.i;
                while matches!(self.peek(), Some(d) if d.is_ascii_digit()) {
                    self.i += 1;
                }
                if self.peek() == Some('.') {
                    return Err((start, "a variable number has no decimal point".into()));
                }
                let t: String = self.c[ds..self.i].iter().collect();
                match t.parse::<i64>() {
                    Ok(n) if n <= 1_000_000 => Ok(VarRef::Num(n)),
                    _ => Err((start, format!("#{t} is not a variable number"))),
                }
            }
            _ => Err((start, "'#' must be followed by a variable number, [expression] or <name>".into())),
        }
    }
}

/// Parses a whole text as one expression (Sinumerik `R3=…`, target files), requiring it to end.
pub fn parse_all(text: &str, syntax: Syntax) -> Result<Expr, ParseError> {
    let chars: Vec<char> = text.chars().collect();
    let mut p = Parser::new(&chars, 0, syntax);
    let e = p.expr()?;
    p.skip_ws();
    if p.i != chars.len() {
        return Err((p.i, format!("unexpected '{}' in the expression", chars[p.i])));
    }
    Ok(e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    struct M(HashMap<VarKey, f64>);
    impl Env for M {
        fn get(&mut self, k: &VarKey) -> Result<Value, String> {
            Ok(self.0.get(k).copied())
        }
        fn exists(&mut self, k: &VarKey) -> bool {
            self.0.contains_key(k)
        }
    }

    fn ev(s: &str, syn: Syntax, vars: &[(i64, f64)]) -> Value {
        let mut m = M(vars.iter().map(|(k, v)| (VarKey::Num(*k), *v)).collect());
        let chars: Vec<char> = s.chars().filter(|c| syn == Syntax::Sinumerik || !c.is_whitespace()).collect();
        let text: String = chars.iter().collect::<String>().to_ascii_uppercase();
        eval(&parse_all(&text, syn).unwrap(), &mut m, 0).unwrap()
    }

    #[test]
    fn macro_b_precedence_functions_and_null() {
        // * above +: 1 + 2·3 = 7; brackets group.
        assert_eq!(ev("1+2*3", Syntax::MacroB, &[]), Some(7.0));
        assert_eq!(ev("[1+2]*3", Syntax::MacroB, &[]), Some(9.0));
        // FUP/FIX from the Fanuc manual's examples.
        assert_eq!(ev("FUP[1.2]", Syntax::MacroB, &[]), Some(2.0));
        assert_eq!(ev("FUP[-1.2]", Syntax::MacroB, &[]), Some(-2.0));
        assert_eq!(ev("FIX[-1.2]", Syntax::MacroB, &[]), Some(-1.0));
        // Null: a bare null stays null, arithmetic reads it as 0, EQ tells it from 0.
        assert_eq!(ev("#1", Syntax::MacroB, &[]), None);
        assert_eq!(ev("#1*5", Syntax::MacroB, &[]), Some(0.0));
        assert_eq!(ev("#0+1", Syntax::MacroB, &[]), Some(1.0));
        assert_eq!(ev("#1EQ#0", Syntax::MacroB, &[]), Some(1.0));
        assert_eq!(ev("#1EQ0", Syntax::MacroB, &[(1, 0.0)]), Some(1.0));
        assert_eq!(ev("#1NE0", Syntax::MacroB, &[]), Some(1.0));
        assert_eq!(ev("#1GE#0", Syntax::MacroB, &[]), Some(1.0));
        assert_eq!(ev("#1GT0", Syntax::MacroB, &[]), Some(0.0));
        // ATAN[-1]/[-1] = 225° in Fanuc's 0 … 360 range, −135° in LinuxCNC's.
        assert!((ev("ATAN[-1]/[-1]", Syntax::MacroB, &[]).unwrap() - 225.0).abs() < 1e-12);
        assert!((ev("ATAN[-1]/[-1]", Syntax::LinuxCnc, &[]).unwrap() + 135.0).abs() < 1e-12);
        // Bitwise OR on integers.
        assert_eq!(ev("5OR2", Syntax::MacroB, &[]), Some(7.0));
    }

    #[test]
    fn linuxcnc_and_dyna_and_sinumerik() {
        assert_eq!(ev("[2**3*2]", Syntax::LinuxCnc, &[]), Some(16.0));
        assert_eq!(ev("[1 LT 2 AND 3 GT 4]", Syntax::LinuxCnc, &[]), Some(0.0));
        assert_eq!(ev("[7 MOD 4]", Syntax::LinuxCnc, &[]), Some(3.0));
        assert!((ev("COS#14", Syntax::Dyna, &[(14, 60.0)]).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(ev("SQR #13", Syntax::Dyna, &[(13, 16.0)]), Some(4.0));
        assert_eq!(ev("R9 - 0.05", Syntax::Sinumerik, &[(9, 1.0)]), Some(0.95));
        assert_eq!(ev("-(R3+1)*2/4", Syntax::Sinumerik, &[(3, 20.0)]), Some(-10.5));
        assert!((ev("SQRT(16)+SIN(30)", Syntax::Sinumerik, &[]).unwrap() - 4.5).abs() < 1e-12);
        assert_eq!(ev("R1 >= 2", Syntax::Sinumerik, &[(1, 2.0)]), Some(1.0));
    }

    #[test]
    fn bad_expressions_are_errors() {
        assert!(parse_all("[1+2", Syntax::MacroB).is_err());
        assert!(parse_all("COS 5", Syntax::MacroB).is_err());
        let deep = "[".repeat(200) + "1" + &"]".repeat(200);
        assert!(parse_all(&deep, Syntax::MacroB).is_err());
        let mut m = M(HashMap::new());
        assert!(eval(&parse_all("1/0", Syntax::MacroB).unwrap(), &mut m, 0).is_err());
    }
}

#[cfg(test)]
mod compiled {
    use super::*;

    struct TZ(f64, f64);
    impl Env for TZ {
        fn get(&mut self, _: &VarKey) -> Result<Value, String> {
            Err("no numbered variables".into())
        }
        fn exists(&mut self, _: &VarKey) -> bool {
            false
        }
        fn get_named(&mut self, n: &str) -> Result<Value, String> {
            match n {
                "t" => Ok(Some(self.0)),
                "z" => Ok(Some(self.1)),
                _ => Err(format!("unknown name {n}")),
            }
        }
    }

    /// The compiled form gives the tree's value bit for bit wherever the tree gives one, and
    /// `None` wherever it gives an error: every operator and function a target formula may use,
    /// over t from −400 to 400 and z from −50 to 10.
    #[test]
    fn compiled_formulas_agree_with_the_tree() {
        let formulas = [
            "20*cos(t)",
            "sqrt(-90*z/4)*sin(t) - 3",
            "(2 + cos(t))^2 / (1 + z*z) - pi",
            "-abs(t - 7) + round(t/3) + exp(z/20) + ln(t*t + 1)",
            "asin(sin(t)/2) + acos(cos(t)/3) + atan(t/100) + tan(t/5)",
            "1/(t - 90) + sqrt(z)",
            "t**2 - z",
        ];
        for f in formulas {
            let e = parse_all(f, Syntax::Formula).unwrap_or_else(|err| panic!("{f}: {err:?}"));
            let c = Compiled::new(&e, &["t", "z"], Arithmetic::Exact).unwrap_or_else(|| panic!("{f}"));
            for i in 0..=160 {
                for j in 0..=12 {
                    let (t, z) = (-400.0 + 5.0 * i as f64, -50.0 + 5.0 * j as f64);
                    let tree = eval(&e, &mut TZ(t, z), 0);
                    match (tree, c.run(&[t, z])) {
                        (Ok(Some(a)), Some(b)) => assert_eq!(a.to_bits(), b.to_bits(), "{f} at t {t}, z {z}"),
                        (Err(_), None) => {}
                        (tree, run) => panic!("{f} at t {t}, z {z}: tree {tree:?}, compiled {run:?}"),
                    }
                }
            }
        }
        // What the compiled form does not read: numbered variables, other names.
        for e in [parse_all("#1+2", Syntax::MacroB).unwrap(), parse_all("t + q", Syntax::Formula).unwrap()] {
            assert!(Compiled::new(&e, &["t", "z"], Arithmetic::Exact).is_none(), "{e:?}");
        }
    }

    struct V(std::collections::HashMap<VarKey, f64>);
    impl Env for V {
        fn get(&mut self, k: &VarKey) -> Result<Value, String> {
            Ok(self.0.get(k).copied())
        }
        fn exists(&mut self, k: &VarKey) -> bool {
            self.0.contains_key(k)
        }
    }

    /// Compiled for an environment, an expression gives the tree's value wherever the tree
    /// gives one, null included (a bare null variable is null, a null operand reads 0), and
    /// `None` wherever the tree gives an error: macro expressions over variables set, unset and
    /// zero, in Fanuc's and LinuxCNC's arithmetic.
    #[test]
    fn compiled_macro_expressions_agree_with_the_tree() {
        let cases = [
            ("#1+#2*3-#3", Syntax::MacroB),
            ("-#3", Syntax::MacroB),
            ("#4", Syntax::MacroB),
            ("[#1+#5]/2", Syntax::MacroB),
            ("SQRT[#1]+ABS[#2]", Syntax::MacroB),
            ("#1/#6", Syntax::MacroB),
            ("ATAN[#1]/[#2]", Syntax::MacroB),
            ("[#1EQ#5]+[#2LT#1]+[#1MOD#2]", Syntax::MacroB),
            ("COS[#1]*SIN[#2]-TAN[#3]", Syntax::MacroB),
            ("[#1**2+#2]/[#6+1]", Syntax::LinuxCnc),
            ("[#1EQ#2]OR[#5LT1]", Syntax::LinuxCnc),
        ];
        for (text, syntax) in cases {
            let e = parse_all(text, syntax).unwrap_or_else(|err| panic!("{text}: {err:?}"));
            for arith in [Arithmetic::Exact, Arithmetic::LinuxCnc] {
                let c = Compiled::for_env(&e, arith).unwrap_or_else(|| panic!("{text}"));
                for (a, b) in [(2.0, 3.0), (-4.5, 0.5), (0.0, -1.0), (1e300, 1e300), (90.0, 0.0)] {
                    for set3 in [false, true] {
                        let mut vars = std::collections::HashMap::new();
                        vars.insert(VarKey::Num(1), a);
                        vars.insert(VarKey::Num(2), b);
                        vars.insert(VarKey::Num(6), 0.0);
                        if set3 {
                            vars.insert(VarKey::Num(3), a - b);
                        }
                        struct A(V, Arithmetic);
                        impl Env for A {
                            fn arithmetic(&self) -> Arithmetic {
                                self.1
                            }
                            fn get(&mut self, k: &VarKey) -> Result<Value, String> {
                                self.0.get(k)
                            }
                            fn exists(&mut self, k: &VarKey) -> bool {
                                self.0.exists(k)
                            }
                        }
                        let tree = eval(&e, &mut A(V(vars.clone()), arith), 0);
                        match (tree, c.run_in(&mut V(vars))) {
                            (Ok(x), Some(y)) => {
                                assert_eq!(x.map(f64::to_bits), y.map(f64::to_bits), "{text} at {a}, {b}")
                            }
                            (Err(_), None) => {}
                            (tree, run) => {
                                panic!("{text} at {a}, {b}, {set3}: tree {tree:?}, compiled {run:?}")
                            }
                        }
                    }
                }
            }
        }
        // An indirect variable is not compiled: the tree reads it.
        assert!(
            Compiled::for_env(&parse_all("#[#1+1]", Syntax::MacroB).unwrap(), Arithmetic::Exact).is_none()
        );
    }
}

#[cfg(test)]
mod x87 {
    /// LinuxCNC's conversions, `(x * M_PIl) / 180.0` and `(x * 180.0) / M_PIl`, compiled with
    /// gcc 12 on x86-64 (long double is the x87's 80 bits) and printed as bits: inputs where
    /// `to_radians`/`to_degrees` are an ulp off. The same program agreed with `deg_to_rad` and
    /// `rad_to_deg` on all of 200 000 inputs (4-decimal values, angles, radians, up to 1e6).
    #[test]
    fn conversions_round_as_linuxcnc_s_long_double() {
        let h = |s: &str| f64::from_bits(u64::from_str_radix(s, 16).unwrap());
        for (x, r) in [
            ("c074190f94ed321f", "c016731690f15e6b"),
            ("c0004df11453cf15", "bfa23656700c6da4"),
            ("3ff852e45230a5ca", "3f9b2b8146f8fd59"),
            ("407427c73a9f4f8f", "40168387118cc483"),
        ] {
            assert_eq!(super::deg_to_rad(h(x)), h(r), "{x}");
            assert_ne!(h(x).to_radians(), h(r), "{x}");
        }
        for (x, d) in [
            ("40708f198bdc1e33", "40cda61437228d94"),
            ("3fc5f02949c579e7", "4023a3d95aa48d9a"),
            ("404ec43c9eecbfb1", "40ab8b2c8222bbed"),
            ("406c64eef64ac9de", "40c96b7cd4fcc60d"),
        ] {
            assert_eq!(super::rad_to_deg(h(x)), h(d), "{x}");
        }
    }
}
