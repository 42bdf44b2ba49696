//! Double-double arithmetic (a value as an unevaluated sum `hi + lo`, about 32 digits).
//!
//! Used only where one rounding of `f64` is not enough: the quarter period K(m) that the
//! argument reduction `u − 2jK` multiplies by up to a few hundred. Written here because the
//! few operations needed (Dekker/Knuth error-free sums and products, Newton square root)
//! do not justify a dependency.

/// A double-double number `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Dd {
    pub hi: f64,
    pub lo: f64,
}

/// π to double-double precision.
pub(crate) const PI: Dd = Dd {
    hi: std::f64::consts::PI,
    lo: 1.224_646_799_147_353_2e-16,
};

fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    Dd { hi: s, lo: e }
}

fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

impl Dd {
    pub fn from_f64(x: f64) -> Self {
        Dd { hi: x, lo: 0.0 }
    }

    pub fn add(self, o: Dd) -> Dd {
        let s = two_sum(self.hi, o.hi);
        let t = two_sum(self.lo, o.lo);
        let r = quick_two_sum(s.hi, s.lo + t.hi);
        quick_two_sum(r.hi, r.lo + t.lo)
    }

    pub fn mul(self, o: Dd) -> Dd {
        let p = self.hi * o.hi;
        let e = self.hi.mul_add(o.hi, -p);
        quick_two_sum(p, e + (self.hi * o.lo + self.lo * o.hi))
    }

    pub fn scale(self, f: f64) -> Dd {
        // exact for powers of two
        Dd {
            hi: self.hi * f,
            lo: self.lo * f,
        }
    }

    pub fn div(self, o: Dd) -> Dd {
        let q1 = self.hi / o.hi;
        let r = self.add(o.mul(Dd::from_f64(-q1)));
        let q2 = r.hi / o.hi;
        let r = r.add(o.mul(Dd::from_f64(-q2)));
        let q3 = r.hi / o.hi;
        quick_two_sum(q1, q2).add(Dd::from_f64(q3))
    }

    pub fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::from_f64(0.0);
        }
        // one Newton step on the double approximation doubles the digits
        let x = self.hi.sqrt();
        let xx = Dd::from_f64(x).mul(Dd::from_f64(x));
        let corr = self.add(Dd {
            hi: -xx.hi,
            lo: -xx.lo,
        });
        quick_two_sum(x, corr.hi / (2.0 * x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sqrt_two_squared_is_two_to_32_digits() {
        let r = Dd::from_f64(2.0).sqrt();
        let sq = r.mul(r).add(Dd::from_f64(-2.0));
        assert!(sq.hi.abs() < 1e-30, "{sq:?}");
    }

    #[test]
    fn division_inverts_multiplication() {
        let a = Dd::from_f64(1.0).div(Dd::from_f64(3.0));
        let back = a.mul(Dd::from_f64(3.0)).add(Dd::from_f64(-1.0));
        assert!(back.hi.abs() < 1e-31, "{back:?}");
    }
}
