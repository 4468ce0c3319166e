//! Rounding floats to whole counts, converting exact integers to
//! floats and floor division, the way every path of the tick does it: the same integer as
//! `libm::round`, at a fraction of its cost where the value is of ordinary
//! size. One home for the rule, so that the coupling law, the steady
//! constants, the ramps and the blend round alike.

/// `v` rounded to the nearest whole number, halves away from zero, as
/// `libm::round` does (up to the sign of a zero result, which no caller
/// can see: every result becomes an integer). Below 2^52 in magnitude,
/// where floats can have a fraction, it truncates with one conversion and
/// looks at the exact remainder; beyond (and for NaN or infinities)
/// `libm::round`, whose software routine costs several times more.
#[inline]
pub(crate) fn round_half_away(v: f64) -> f64 {
    if v > -4.5e15 && v < 4.5e15 {
        let whole = v as i64 as f64;
        // Exact: both are within 2^52 and `whole` is `v` without its fraction.
        let fraction = v - whole;
        // Selects, not branches: the fraction is as good as random from
        // tick to tick, and a mispredicted branch costs more than the sum.
        let up = if fraction >= 0.5 { 1.0 } else { 0.0 };
        let down = if fraction <= -0.5 { 1.0 } else { 0.0 };
        whole + up - down
    } else {
        libm::round(v)
    }
}

/// [`round_half_away`] as an `i64`, `None` when the result is not finite
/// or leaves ±9.2·10^18. Below 2^52 the truncation is already the integer,
/// so the common case needs no conversion back to a float.
#[inline(always)]
pub(crate) fn round_to_i64(v: f64) -> Option<i64> {
    if v > -4.5e15 && v < 4.5e15 {
        let whole = v as i64;
        // Exact, as in `round_half_away`; the adjustments are selects.
        let fraction = v - whole as f64;
        Some(whole + i64::from(fraction >= 0.5) - i64::from(fraction <= -0.5))
    } else {
        let r = libm::round(v);
        // Strictly inside ±2^63, so the conversion is exact.
        (r > -9.2e18 && r < 9.2e18).then_some(r as i64)
    }
}

/// `v` rounded to the nearest whole number, halves up: `floor(v + ½)`
/// taken exactly. The cam law rounds with it (docs/engine.md, "The
/// coupling law") because it commutes with whole numbers: `n +
/// round_half_up(y) = round_half_up(n + y)`. The law splits a value into
/// a whole part and a fraction, and that split differs on the two sides of
/// a seam (cycle `k`'s end, cycle `k + 1`'s start) for the same value; a
/// rounding that depends on the split (halves away from zero) could put
/// the two sides a pulse apart, a reversal the master never made. `None`
/// when the result is not finite or leaves ±9.2·10^18.
#[inline(always)]
pub(crate) fn round_half_up_to_i64(v: f64) -> Option<i64> {
    if v > -4.5e15 && v < 4.5e15 {
        let whole = v as i64;
        // Exact, as in `round_half_away`: a negative half stays at the
        // truncation (up), only a fraction below it goes down.
        let fraction = v - whole as f64;
        Some(whole + i64::from(fraction >= 0.5) - i64::from(fraction < -0.5))
    } else {
        // Beyond 2^52 every float is whole: it is its own rounding.
        let r = libm::round(v);
        (r > -9.2e18 && r < 9.2e18).then_some(r as i64)
    }
}

/// [`round_half_up_to_i64`] as a float, for the 128-bit route (any size;
/// NaN and infinities pass through for the caller to report).
#[inline]
pub(crate) fn round_half_up(v: f64) -> f64 {
    if v > -4.5e15 && v < 4.5e15 {
        let whole = v as i64 as f64;
        let fraction = v - whole;
        let up = if fraction >= 0.5 { 1.0 } else { 0.0 };
        let down = if fraction < -0.5 { 1.0 } else { 0.0 };
        whole + up - down
    } else {
        libm::round(v)
    }
}

/// `v as f64`, bit for bit, without the 128-bit library routine where
/// `v` fits 64 bits (nearly always).
#[inline]
pub(crate) fn exact_f64(v: i128) -> f64 {
    match i64::try_from(v) {
        Ok(small) => small as f64,
        Err(_) => wide_to_f64(v),
    }
}

/// The 128-bit conversion, out of line: inlined, the compiler sees that
/// both arms of [`exact_f64`] give the same float and keeps only this
/// one, the library routine, for every value (about 45 instructions
/// instead of one).
#[cold]
#[inline(never)]
fn wide_to_f64(v: i128) -> f64 {
    v as f64
}

/// `v` as a float, for a count that is never negative (travel, spans):
/// one conversion below 2^64, where every such value lies in practice.
#[inline]
pub(crate) fn unsigned_to_f64(v: u128) -> f64 {
    match u64::try_from(v) {
        Ok(small) => small as f64,
        Err(_) => wide_unsigned_to_f64(v),
    }
}

/// [`wide_to_f64`] for [`unsigned_to_f64`].
#[cold]
#[inline(never)]
fn wide_unsigned_to_f64(v: u128) -> f64 {
    v as f64
}

/// `libm::ceil(v)` in a few instructions: below 2^52 a float's whole
/// part is one truncating conversion away, and from there up every float
/// is whole already (as are the infinities; NaN stays NaN). The same
/// value, except that a `v` in (−1, 0) gives +0 where `libm::ceil` gives
/// −0, which compare equal.
#[inline]
pub(crate) fn ceil_whole(v: f64) -> f64 {
    if libm::fabs(v) < 4_503_599_627_370_496.0 {
        let truncated = v as i64 as f64;
        if truncated < v {
            truncated + 1.0
        } else {
            truncated
        }
    } else {
        v
    }
}

/// `v.ceil() as i128` (saturating, NaN as 0) with one conversion where
/// the result fits 64 bits; the same integer.
#[inline]
pub(crate) fn ceil_to_i128(v: f64) -> i128 {
    let up = libm::ceil(v);
    if up > -9.2e18 && up < 9.2e18 {
        i128::from(up as i64)
    } else {
        wide_from_f64(up)
    }
}

/// A whole float (already rounded) as an integer, saturating (NaN as 0):
/// one conversion below ±9·10¹⁸, the 128-bit one beyond, out of line.
#[inline]
pub(crate) fn whole_to_i128(v: f64) -> i128 {
    if v > -9.0e18 && v < 9.0e18 {
        i128::from(v as i64)
    } else {
        wide_from_f64(v)
    }
}

/// The 128-bit conversion of [`ceil_to_i128`] and [`whole_to_i128`], out
/// of line (see [`wide_to_f64`]).
#[cold]
#[inline(never)]
fn wide_from_f64(v: f64) -> i128 {
    v as i128
}

/// `libm::round(v) as i128` (saturating, NaN as 0) with the fast rounding
/// of [`round_to_i64`] where it applies: the same integer.
#[inline]
pub(crate) fn round_to_i128(v: f64) -> i128 {
    match round_to_i64(v) {
        Some(whole) => i128::from(whole),
        None => libm::round(v) as i128,
    }
}

/// `(a.div_euclid(b), a.rem_euclid(b))` for `b > 0`, from one hardware
/// division (the two library calls take one each, and are not always
/// inlined): the same pair (tested).
#[inline(always)]
pub(crate) fn floor_div_rem(a: i64, b: i64) -> (i64, i64) {
    debug_assert!(b > 0);
    let (q, r) = (a.wrapping_div(b), a.wrapping_rem(b));
    if r < 0 { (q - 1, r + b) } else { (q, r) }
}

/// Pseudo-random words (xorshift64) from a non-zero seed, for the tests
/// that compare two routes over many values.
#[cfg(test)]
pub(crate) fn xorshift(seed: u64) -> impl Iterator<Item = u64> {
    core::iter::successors(Some(seed), |&x| {
        let x = x ^ (x << 13);
        let x = x ^ (x >> 7);
        Some(x ^ (x << 17))
    })
    .skip(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_div_rem_is_div_euclid_and_rem_euclid() {
        let mut words = xorshift(0x1234_5678_9ABC_DEF1);
        for _ in 0..100_000 {
            let a = words.next().unwrap_or(1) as i64;
            let b = (words.next().unwrap_or(1) >> (words.next().unwrap_or(1) % 63)) as i64;
            for (a, b) in [
                (a, b.max(1)),
                (a >> 40, (b >> 50).max(1)),
                (i64::MIN, b.max(1)),
            ] {
                assert_eq!(
                    floor_div_rem(a, b),
                    (a.div_euclid(b), a.rem_euclid(b)),
                    "{a} {b}"
                );
            }
        }
    }

    #[test]
    fn conversions_give_the_plain_casts_values() {
        let wide = [
            0i128,
            1,
            -1,
            (1 << 53) + 1,
            -(1 << 53) - 1,
            i128::from(i64::MAX),
            i128::from(i64::MIN),
            i128::from(i64::MAX) + 1,
            i128::from(i64::MIN) - 1,
            i128::MAX,
            i128::MIN,
            12_345_678_901_234_567_890_123,
        ];
        for v in wide {
            assert_eq!(exact_f64(v).to_bits(), (v as f64).to_bits(), "{v}");
            let u = v.unsigned_abs();
            assert_eq!(unsigned_to_f64(u).to_bits(), (u as f64).to_bits(), "{u}");
        }
        for v in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0000001,
            9.1e18,
            -9.1e18,
            9.3e18,
            -9.3e18,
            1e30,
            -1e30,
            1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ] {
            assert_eq!(ceil_to_i128(v), libm::ceil(v) as i128, "{v}");
        }
    }

    #[test]
    fn ceil_whole_is_libm_ceil() {
        let same = |v: f64| {
            let (a, b) = (ceil_whole(v), libm::ceil(v));
            a == b || (a.is_nan() && b.is_nan())
        };
        let edges = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            1.0 + f64::EPSILON,
            -1.0000001,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            9.3e18,
            -9.3e18,
            1e300,
            f64::MIN_POSITIVE,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for v in edges {
            assert!(same(v), "{v}");
        }
        let mut words = xorshift(0x0DDB_A11C_0FFE_E000);
        for _ in 0..100_000 {
            let bits = words.next().unwrap_or(0);
            // Any float, and floats of every size near whole counts.
            let near =
                (bits % 1_000_000) as f64 * 0.25 * libm::exp2(f64::from((bits >> 40) as u8 % 64));
            for v in [f64::from_bits(bits), near, -near, near + 0.5] {
                assert!(same(v), "{v}");
            }
        }
    }

    #[test]
    fn round_half_away_is_libm_round() {
        let same = |v: f64| {
            let (a, b) = (round_half_away(v), libm::round(v));
            a == b || (a.is_nan() && b.is_nan())
        };
        for v in [
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            0.49999999999999994,
            -0.49999999999999994,
            4.5e15 - 0.5,
            -4.5e15 + 0.5,
            4.5e15,
            1e300,
            -0.0,
            f64::INFINITY,
            f64::NAN,
        ] {
            assert!(same(v), "{v}");
        }
        for x in xorshift(0x9E37_79B9_7F4A_7C15).take(100_000) {
            let v = f64::from_bits(x);
            let scaled = (x >> 11) as f64 / (1u64 << 53) as f64 * 1e6 - 5e5;
            assert!(same(v) && same(scaled), "{v} {scaled}");
        }
    }

    #[test]
    fn round_to_i64_is_the_rounded_float_converted() {
        let reference = |v: f64| {
            let r = round_half_away(v);
            (r > -9.2e18 && r < 9.2e18).then_some(r as i64)
        };
        for v in [
            0.5,
            -0.5,
            2.5,
            -2.5,
            0.49999999999999994,
            -0.49999999999999994,
            4.5e15 - 0.5,
            -4.5e15 + 0.5,
            4.5e15 + 0.5,
            -4.5e15 - 0.5,
            9.2e18,
            -9.2e18,
            9.1e18,
            1e300,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ] {
            assert_eq!(round_to_i64(v), reference(v), "{v}");
        }
        for x in xorshift(0x2545_F491_4F6C_DD1D).take(100_000) {
            let v = f64::from_bits(x);
            let scaled = (x >> 11) as f64 / (1u64 << 53) as f64 * 1e7 - 5e6;
            let near = 4.5e15 + ((x % 4096) as f64 - 2048.0) * 0.5;
            for w in [v, scaled, near, -near] {
                assert_eq!(round_to_i64(w), reference(w), "{w}");
            }
        }
    }

    /// `floor(v + ½)` taken exactly: the floor and the exact remainder
    /// above it (no float addition that could round a value just under a
    /// half up to it).
    fn half_up_reference(v: f64) -> f64 {
        if !v.is_finite() || v.abs() >= 4.5e15 {
            return libm::round(v);
        }
        let floor = libm::floor(v);
        if v - floor >= 0.5 { floor + 1.0 } else { floor }
    }

    #[test]
    fn round_half_up_is_floor_of_v_plus_a_half() {
        let same = |v: f64| {
            let (a, b) = (round_half_up(v), half_up_reference(v));
            let int = (b > -9.2e18 && b < 9.2e18).then_some(b as i64);
            (a == b || (a.is_nan() && b.is_nan())) && round_half_up_to_i64(v) == int
        };
        for v in [
            0.5,
            -0.5,
            1.5,
            -1.5,
            -2.5,
            -0.5000000000000001,
            0.49999999999999994,
            -0.49999999999999994,
            4.5e15 - 0.5,
            -4.5e15 + 0.5,
            9.3e18,
            1e300,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ] {
            assert!(same(v), "{v}");
        }
        assert_eq!(round_half_up_to_i64(-0.5), Some(0));
        assert_eq!(round_half_up_to_i64(-1.5), Some(-1));
        assert_eq!(round_half_up_to_i64(-1.5000001), Some(-2));
        for x in xorshift(0x6A09_E667_F3BC_C909).take(100_000) {
            let v = f64::from_bits(x);
            let scaled = (x >> 11) as f64 / (1u64 << 53) as f64 * 1e6 - 5e5;
            let halves = ((x >> 20) % 20_001) as f64 * 0.5 - 5000.0;
            assert!(
                same(v) && same(scaled) && same(halves),
                "{v} {scaled} {halves}"
            );
        }
    }

    /// The property the cam law needs: a whole number added before or
    /// after the rounding gives the same result (halves away from zero
    /// does not: -0.5 + 1 against 0.5).
    #[test]
    fn round_half_up_commutes_with_whole_numbers() {
        let mut words = xorshift(0xBB67_AE85_84CA_A73B);
        for _ in 0..100_000 {
            let (a, b) = (words.next().unwrap_or(1), words.next().unwrap_or(1));
            let n = (a >> 44) as i64 - (1 << 19);
            // Quarters, so exact halves come up often.
            let y = ((b >> 40) as i64 - (1 << 23)) as f64 / 4.0;
            assert_eq!(
                round_half_up_to_i64(n as f64 + y),
                round_half_up_to_i64(y).map(|r| r + n),
                "{n} {y}"
            );
        }
        assert_ne!(
            round_to_i64(-0.5).map(|r| r + 1),
            round_to_i64(0.5),
            "halves away from zero depend on the split"
        );
    }
}
