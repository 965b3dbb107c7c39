//! OpenSCENARIO 1.2 expressions, `${…}` in an attribute: numbers, parameters
//! (`$name`), `+ - * / %`, unary minus, parentheses, `not`, `and`, `or`, the
//! comparisons `== != < <= > >=` (true is 1, false 0), and the functions `round`,
//! `floor`, `ceil`, `sqrt`, `pow`, `sin`, `cos`, `tan`, `asin`, `acos`, `atan`, `abs`,
//! `min`, `max`. Evaluated in double precision by recursive descent.

/// The value of `text` (the inside of `${…}`), `parameter` giving each `$name`'s.
pub fn evaluate(
    text: &str,
    parameter: &dyn Fn(&str) -> Result<f64, String>,
) -> Result<f64, String> {
    let tokens = tokens(text)?;
    let mut p = Parser {
        tokens: &tokens,
        at: 0,
        parameter,
        depth: 0,
    };
    let v = p.or()?;
    match p.tokens.get(p.at) {
        None => Ok(v),
        Some(t) => Err(format!("unexpected `{t}` in `{text}`")),
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Number(f64),
    Parameter(String),
    Word(String),
    Symbol(&'static str),
}

impl std::fmt::Display for Token {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Number(n) => write!(f, "{n}"),
            Self::Parameter(p) => write!(f, "${p}"),
            Self::Word(w) => write!(f, "{w}"),
            Self::Symbol(s) => write!(f, "{s}"),
        }
    }
}

const SYMBOLS: [&str; 14] = [
    "==", "!=", "<=", ">=", "<", ">", "+", "-", "*", "/", "%", "(", ")", ",",
];

fn tokens(text: &str) -> Result<Vec<Token>, String> {
    let mut out = Vec::new();
    let mut rest = text.trim_start();
    while !rest.is_empty() {
        let c = rest.chars().next().unwrap_or(' ');
        let word_len = |s: &str| {
            s.find(|ch: char| !(ch.is_alphanumeric() || ch == '_'))
                .unwrap_or(s.len())
        };
        if c.is_ascii_digit() || c == '.' {
            let mut end = rest
                .find(|ch: char| !(ch.is_ascii_digit() || ch == '.'))
                .unwrap_or(rest.len());
            // An exponent: 1e-3, 2.5E+2.
            if rest[end..].starts_with(['e', 'E']) {
                let after = &rest[end + 1..];
                let sign = usize::from(after.starts_with(['+', '-']));
                let digits = after[sign..]
                    .find(|ch: char| !ch.is_ascii_digit())
                    .unwrap_or(after.len() - sign);
                if digits > 0 {
                    end += 1 + sign + digits;
                }
            }
            let n: f64 = rest[..end]
                .parse()
                .map_err(|_| format!("`{}` is not a number", &rest[..end]))?;
            out.push(Token::Number(n));
            rest = &rest[end..];
        } else if c == '$' {
            let len = word_len(&rest[1..]);
            if len == 0 {
                return Err(format!("`$` without a parameter's name in `{text}`"));
            }
            out.push(Token::Parameter(rest[1..=len].to_owned()));
            rest = &rest[1 + len..];
        } else if c.is_alphabetic() {
            let len = word_len(rest);
            out.push(Token::Word(rest[..len].to_owned()));
            rest = &rest[len..];
        } else if let Some(s) = SYMBOLS.iter().find(|s| rest.starts_with(**s)) {
            out.push(Token::Symbol(s));
            rest = &rest[s.len()..];
        } else {
            return Err(format!("`{c}` cannot stand in an expression (`{text}`)"));
        }
        rest = rest.trim_start();
    }
    Ok(out)
}

/// How deeply parentheses, function calls and signs may nest: a file may hold any
/// text, and each level is a call on the stack.
const MAX_NESTING: u32 = 64;

struct Parser<'a> {
    tokens: &'a [Token],
    at: usize,
    parameter: &'a dyn Fn(&str) -> Result<f64, String>,
    depth: u32,
}

fn truth(b: bool) -> f64 {
    if b { 1.0 } else { 0.0 }
}

impl Parser<'_> {
    fn peek_symbol(&self, s: &str) -> bool {
        matches!(self.tokens.get(self.at), Some(Token::Symbol(t)) if *t == s)
    }

    fn peek_word(&self, w: &str) -> bool {
        matches!(self.tokens.get(self.at), Some(Token::Word(t)) if t == w)
    }

    fn expect(&mut self, s: &str) -> Result<(), String> {
        if self.peek_symbol(s) {
            self.at += 1;
            Ok(())
        } else {
            Err(format!("`{s}` expected"))
        }
    }

    fn or(&mut self) -> Result<f64, String> {
        let mut v = self.and()?;
        while self.peek_word("or") {
            self.at += 1;
            let r = self.and()?;
            v = truth(v != 0.0 || r != 0.0);
        }
        Ok(v)
    }

    fn and(&mut self) -> Result<f64, String> {
        let mut v = self.comparison()?;
        while self.peek_word("and") {
            self.at += 1;
            let r = self.comparison()?;
            v = truth(v != 0.0 && r != 0.0);
        }
        Ok(v)
    }

    #[expect(
        clippy::float_cmp,
        reason = "an expression's == and != compare its numbers exactly, as the standard's"
    )]
    fn comparison(&mut self) -> Result<f64, String> {
        let v = self.sum()?;
        for op in ["==", "!=", "<=", ">=", "<", ">"] {
            if self.peek_symbol(op) {
                self.at += 1;
                let r = self.sum()?;
                return Ok(truth(match op {
                    "==" => v == r,
                    "!=" => v != r,
                    "<=" => v <= r,
                    ">=" => v >= r,
                    "<" => v < r,
                    _ => v > r,
                }));
            }
        }
        Ok(v)
    }

    fn sum(&mut self) -> Result<f64, String> {
        let mut v = self.product()?;
        loop {
            if self.peek_symbol("+") {
                self.at += 1;
                v += self.product()?;
            } else if self.peek_symbol("-") {
                self.at += 1;
                v -= self.product()?;
            } else {
                return Ok(v);
            }
        }
    }

    fn product(&mut self) -> Result<f64, String> {
        let mut v = self.unary()?;
        loop {
            if self.peek_symbol("*") {
                self.at += 1;
                v *= self.unary()?;
            } else if self.peek_symbol("/") {
                self.at += 1;
                let r = self.unary()?;
                if r == 0.0 {
                    return Err("division by zero".into());
                }
                v /= r;
            } else if self.peek_symbol("%") {
                self.at += 1;
                let r = self.unary()?;
                if r == 0.0 {
                    return Err("remainder of a division by zero".into());
                }
                v %= r;
            } else {
                return Ok(v);
            }
        }
    }

    /// Every nesting passes here: counted, so nothing a file says overflows the
    /// stack.
    fn unary(&mut self) -> Result<f64, String> {
        self.depth += 1;
        if self.depth > MAX_NESTING {
            return Err(format!(
                "the expression nests deeper than {MAX_NESTING} levels"
            ));
        }
        let v = self.signed();
        self.depth -= 1;
        v
    }

    fn signed(&mut self) -> Result<f64, String> {
        if self.peek_symbol("-") {
            self.at += 1;
            return Ok(-self.unary()?);
        }
        if self.peek_word("not") {
            self.at += 1;
            let v = self.unary()?;
            return Ok(truth(v == 0.0));
        }
        self.primary()
    }

    fn primary(&mut self) -> Result<f64, String> {
        let token = self
            .tokens
            .get(self.at)
            .cloned()
            .ok_or("the expression ends too early")?;
        self.at += 1;
        match token {
            Token::Number(n) => Ok(n),
            Token::Parameter(name) => (self.parameter)(&name),
            Token::Symbol("(") => {
                let v = self.or()?;
                self.expect(")")?;
                Ok(v)
            }
            Token::Word(w) if w == "true" => Ok(1.0),
            Token::Word(w) if w == "false" => Ok(0.0),
            Token::Word(f) => {
                self.expect("(")?;
                let mut args = vec![self.or()?];
                while self.peek_symbol(",") {
                    self.at += 1;
                    args.push(self.or()?);
                }
                self.expect(")")?;
                call(&f, &args)
            }
            Token::Symbol(s) => Err(format!("unexpected `{s}`")),
        }
    }
}

fn call(f: &str, args: &[f64]) -> Result<f64, String> {
    let one = |g: fn(f64) -> f64| match args {
        [x] => Ok(g(*x)),
        _ => Err(format!("{f} takes one argument")),
    };
    let two = |g: fn(f64, f64) -> f64| match args {
        [x, y] => Ok(g(*x, *y)),
        _ => Err(format!("{f} takes two arguments")),
    };
    let v = match f {
        "round" => one(f64::round),
        "floor" => one(f64::floor),
        "ceil" => one(f64::ceil),
        "sqrt" => one(f64::sqrt),
        "sin" => one(f64::sin),
        "cos" => one(f64::cos),
        "tan" => one(f64::tan),
        "asin" => one(f64::asin),
        "acos" => one(f64::acos),
        "atan" => one(f64::atan),
        "abs" => one(f64::abs),
        "pow" => two(f64::powf),
        "min" => two(f64::min),
        "max" => two(f64::max),
        _ => Err(format!(
            "`{f}` is not a function of OpenSCENARIO expressions"
        )),
    }?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("{f}({args:?}) is not a finite number"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(text: &str) -> Result<f64, String> {
        evaluate(text, &|name| match name {
            "Range" => Ok(2_000.0),
            "Half" => Ok(0.5),
            _ => Err(format!("no parameter {name}")),
        })
    }

    #[test]
    fn arithmetic_parameters_functions_and_logic() {
        let close = |text: &str, want: f64| {
            let v = eval(text).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert!((v - want).abs() < 1e-9, "{text} = {v}, not {want}");
        };
        close("1 + 2 * 3", 7.0);
        close("(1 + 2) * 3", 9.0);
        close("-$Range / 4 + 10 % 4", -498.0);
        close("$Range * $Half", 1_000.0);
        close(
            "pow(2, 10) + sqrt(16) + round(2.5) + floor(-1.5)",
            1_028.0 + 1.0,
        );
        close("1.5e3 - 2E-1", 1_499.8);
        close("$Range > 1000 and not ($Half == 1) or false", 1.0);
        close("max(1, min(3, 2))", 2.0);
        for bad in [
            "1 +",
            "(1",
            "$Nope + 1",
            "1 / 0",
            "cube(2)",
            "1 # 2",
            "2 3",
            "sqrt(1, 2)",
        ] {
            assert!(eval(bad).is_err(), "{bad}");
        }
        // Nesting is bounded, not a stack overflow: 60 levels read, 100 000 refused.
        close(&format!("{}1{}", "(".repeat(60), ")".repeat(60)), 1.0);
        let deep = format!("{}1{}", "(".repeat(100_000), ")".repeat(100_000));
        assert!(eval(&deep).expect_err("too deep").contains("nests deeper"));
        assert!(eval(&"-".repeat(100_000)).is_err());
    }
}
