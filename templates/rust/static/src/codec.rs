//! The encoding rules every canspec language shares: physical → raw rounding, range checks,
//! rolling counters. The C and Python bindings implement the same rules step for step.

pub use crate::constants::{EXACT_LIMIT, TIE_EPSILON};

/// The scaling and the allowed range of one scaled signal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale {
    /// physical = raw × factor + offset
    pub factor: f64,
    /// physical = raw × factor + offset
    pub offset: f64,
    /// Smallest physical value a caller may pass (the documented range).
    pub check_min: f64,
    /// Largest physical value a caller may pass (the documented range).
    pub check_max: f64,
    /// Smallest raw value a physical encode may produce.
    pub raw_min: i64,
    /// Largest raw value a physical encode may produce.
    pub raw_max: i64,
    /// Smallest raw value the field's bits hold.
    pub type_min: i64,
    /// Largest raw value the field's bits hold.
    pub type_max: i64,
}

/// 1.5 × 2^52: adding it to `0 <= t < 2^51` leaves `t` rounded to an integer in the low
/// mantissa bits.
const ROUNDING_MAGIC: f64 = 6_755_399_441_055_744.0;

/// `floor(t)` for finite `|t| < 2^62` without `std` (core has no `f64::floor`).
#[inline(always)]
fn floor_i64(t: f64) -> i64 {
    if (0.0..2_251_799_813_685_248.0).contains(&t) {
        // Round to nearest through the magic constant (no saturating conversion), then step
        // down where that rounded up.
        let shifted = t + ROUNDING_MAGIC;
        let nearest = shifted.to_bits() as i64 - ROUNDING_MAGIC.to_bits() as i64;
        nearest - ((shifted - ROUNDING_MAGIC) > t) as i64
    } else {
        let truncated = t as i64; // rounds toward zero, exact in this range
        truncated - ((truncated as f64) > t) as i64
    }
}

/// Round half away from zero, the shared runtime rule: with `a = |q|`,
/// `a >= EXACT_LIMIT ? q : ±floor((a + 0.5) + ε)` (from 2^52 up every double is an integer,
/// and adding 0.5 would round to even). `q` must be finite; beyond ±2^63 the result saturates.
#[inline(always)]
pub fn round_half_away(q: f64) -> i64 {
    let a = f64::from_bits(q.to_bits() & !(1 << 63)); // |q|
    if a >= EXACT_LIMIT {
        return q as i64;
    }
    let magnitude = floor_i64((a + 0.5) + TIE_EPSILON);
    if q >= 0.0 {
        magnitude
    } else {
        -magnitude
    }
}

/// 2^63: the doubles in [-2^63, 2^63) are those whose rounding (an integer double from
/// [`EXACT_LIMIT`] up) an `i64` holds.
const TWO_POW_63: f64 = 9_223_372_036_854_775_808.0;

/// The field check of the shared rule (ir/encoding.py `fits_runtime`): `q` rounds to `raw`, a
/// value the field's bits hold. The rounding saturates beyond ±2^63 and NaN gives 0, so `q`
/// is first held to where the rounding is exact (NaN lies in no range).
#[inline(always)]
fn lands_in_field(q: f64, raw: i64, type_min: i64, type_max: i64) -> bool {
    (-TWO_POW_63..TWO_POW_63).contains(&q) & (type_min..=type_max).contains(&raw)
}

/// Physical → raw with the shared rules, or `None` when the value may not be sent: NaN,
/// outside what the field holds, or outside the documented range unless the raw value is one
/// of `specials`. Never wraps or clamps.
#[inline(always)]
pub fn to_raw(value: f64, scale: &Scale, specials: &[i64]) -> Option<i64> {
    let q = (value - scale.offset) / scale.factor;
    // The rounding first, then whether it lands in the field: a decoded value at the field's
    // end encodes back however far a double's step puts its quotient beyond the end.
    let raw = round_half_away(q);
    let fits = lands_in_field(q, raw, scale.type_min, scale.type_max);
    let documented = (value >= scale.check_min)
        & (value <= scale.check_max)
        & (raw >= scale.raw_min)
        & (raw <= scale.raw_max);
    if fits & (documented || specials.contains(&raw)) {
        Some(raw)
    } else {
        None
    }
}

/// The scaling and the allowed range of a scaled 64-bit unsigned field, whose raw values
/// reach beyond `i64`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScaleU64 {
    /// physical = raw × factor + offset
    pub factor: f64,
    /// physical = raw × factor + offset
    pub offset: f64,
    /// Smallest physical value a caller may pass (the documented range).
    pub check_min: f64,
    /// Largest physical value a caller may pass (the documented range).
    pub check_max: f64,
    /// Smallest raw value a physical encode may produce.
    pub raw_min: u64,
    /// Largest raw value a physical encode may produce.
    pub raw_max: u64,
}

/// 2^64: the doubles below it are exactly those whose rounding a `u64` holds (none lies
/// between `u64::MAX` and it).
const TWO_POW_64: f64 = 18_446_744_073_709_551_616.0;

/// [`to_raw`] for a [`ScaleU64`] field (it holds every `u64`).
#[inline]
pub fn to_raw_u64(value: f64, scale: &ScaleU64, specials: &[u64]) -> Option<u64> {
    let q = (value - scale.offset) / scale.factor;
    // The rounding lands in the field (see [`lands_in_field`]): a negative `q` must round to 0
    // by the rule's own steps on |q| (NaN fails `q < TWO_POW_64`, -∞ rounds to `i64::MIN`).
    let fits = if q < 0.0 {
        round_half_away(q) == 0
    } else {
        q < TWO_POW_64
    };
    // For a `q` that fits, this is `round_half_away` (a negative `q` that fits gives 0 too).
    let raw = if q >= EXACT_LIMIT {
        q as u64
    } else {
        floor_i64((q + 0.5) + TIE_EPSILON) as u64
    };
    let documented = (value >= scale.check_min)
        & (value <= scale.check_max)
        & (raw >= scale.raw_min)
        & (raw <= scale.raw_max);
    if fits & (documented || specials.contains(&raw)) {
        Some(raw)
    } else {
        None
    }
}

/// The scaling and the allowed range of a signal whose factor and offset are integers, so
/// that its physical values are integers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IntScale {
    /// physical = raw × factor + offset
    pub factor: i64,
    /// physical = raw × factor + offset
    pub offset: i64,
    /// Smallest physical value a caller may pass (the documented range).
    pub check_min: i64,
    /// Largest physical value a caller may pass (the documented range).
    pub check_max: i64,
    /// Smallest raw value a physical encode may produce.
    pub raw_min: i64,
    /// Largest raw value a physical encode may produce.
    pub raw_max: i64,
    /// Smallest raw value the field's bits hold.
    pub type_min: i64,
    /// Largest raw value the field's bits hold.
    pub type_max: i64,
}

/// [`to_raw`] for an integer physical value of an [`IntScale`] signal, in exact integer
/// arithmetic: for factors below 5·10⁸ it gives the same result as the double rule (a
/// quotient that is not a tie lies at least 1/(2·factor) from one, far beyond the epsilon).
#[inline(always)]
pub fn to_raw_int(value: i64, scale: &IntScale, specials: &[i64]) -> Option<i64> {
    let n = value - scale.offset;
    let magnitude = (2 * n.abs() + scale.factor) / (2 * scale.factor);
    let raw = if n >= 0 { magnitude } else { -magnitude };
    // The rounding lands in the field (the shared rule's field check, exact here).
    let fits = (raw >= scale.type_min) & (raw <= scale.type_max);
    let documented = (value >= scale.check_min)
        & (value <= scale.check_max)
        & (raw >= scale.raw_min)
        & (raw <= scale.raw_max);
    if fits & (documented || specials.contains(&raw)) {
        Some(raw)
    } else {
        None
    }
}

/// [`to_raw`] for a signal without special values whose documented range the generator has
/// proven to imply the other checks (q inside the field, raw inside its allowed range): the
/// same result with one range check.
#[inline(always)]
pub fn to_raw_documented(value: f64, scale: &Scale) -> Option<i64> {
    if (value >= scale.check_min) & (value <= scale.check_max) {
        Some(round_half_away((value - scale.offset) / scale.factor))
    } else {
        None
    }
}

/// [`to_raw_documented`] where the documented range also makes `q` non-negative and below
/// [`EXACT_LIMIT`] (the rounding's first branch never applies).
#[inline(always)]
pub fn to_raw_documented_unsigned(value: f64, scale: &Scale) -> Option<i64> {
    if (value >= scale.check_min) & (value <= scale.check_max) {
        Some(floor_i64(
            ((value - scale.offset) / scale.factor + 0.5) + TIE_EPSILON,
        ))
    } else {
        None
    }
}

/// 1.5 × 2^20: adding it to `0 <= t < 2^19` leaves `t` rounded to a multiple of 2^-32 in
/// the low mantissa bits, so the bits hold `t` in 32.32 fixed point.
const FIXED_POINT_MAGIC: f64 = 1_572_864.0;

/// [`to_raw_documented_unsigned`] with a multiplication by `reciprocal` (the double nearest
/// 1/factor) instead of the division, for signals whose quotients stay below 2^17. One
/// addition puts the product, 0.5 and the epsilon into 32.32 fixed point (the constant and
/// the sum each rounded to 2^-32: 1 · 2^-32 together); the product lies within 3 units in the
/// last place (0.19 · 2^-32) of the rule's quotient, whose two roundings move it by at most
/// another 0.13 · 2^-32. A fraction at least 2 · 2^-32 from a whole number therefore floors
/// to the rule's integer; closer (never for decimal ties, whose epsilon keeps them 4.3 · 2^-32
/// above one), the division decides. The same result as the division rule.
#[inline(always)]
pub fn to_raw_documented_unsigned_recip(value: f64, scale: &Scale, reciprocal: f64) -> Option<i64> {
    if (value >= scale.check_min) & (value <= scale.check_max) {
        let v = value - scale.offset;
        let sum = v * reciprocal + (FIXED_POINT_MAGIC + (0.5 + TIE_EPSILON));
        let fixed = sum.to_bits().wrapping_sub(FIXED_POINT_MAGIC.to_bits());
        if (fixed as u32).wrapping_sub(2) <= u32::MAX - 4 {
            Some((fixed >> 32) as i64)
        } else {
            Some(floor_i64((v / scale.factor + 0.5) + TIE_EPSILON))
        }
    } else {
        None
    }
}

/// [`to_raw_documented`] for a signal with special values: inside the documented range the
/// shortcut, outside it the full rule (which lets the special values through).
#[inline(always)]
pub fn to_raw_documented_or_special(value: f64, scale: &Scale, specials: &[i64]) -> Option<i64> {
    match to_raw_documented(value, scale) {
        Some(raw) => Some(raw),
        None => to_raw(value, scale, specials),
    }
}

/// [`to_raw_int`] for a signal the generator has proven its documented range suffices for
/// (see [`to_raw_documented`]).
#[inline(always)]
pub fn to_raw_int_documented(value: i64, scale: &IntScale) -> Option<i64> {
    if (value >= scale.check_min) & (value <= scale.check_max) {
        let n = value - scale.offset;
        let magnitude = (2 * n.abs() + scale.factor) / (2 * scale.factor);
        Some(if n >= 0 { magnitude } else { -magnitude })
    } else {
        None
    }
}

/// [`to_raw_int_documented`] for a signal with special values (see
/// [`to_raw_documented_or_special`]).
#[inline(always)]
pub fn to_raw_int_documented_or_special(
    value: i64,
    scale: &IntScale,
    specials: &[i64],
) -> Option<i64> {
    match to_raw_int_documented(value, scale) {
        Some(raw) => Some(raw),
        None => to_raw_int(value, scale, specials),
    }
}

/// XOR of the eight bytes of a frame word.
#[inline(always)]
pub const fn xor_bytes(word: u64) -> u8 {
    let word = word ^ (word >> 32);
    let word = word ^ (word >> 16);
    (word ^ (word >> 8)) as u8
}

/// The value after `value` of a rolling counter of `bits` bits (wraps to 0).
#[inline]
pub const fn next_counter(value: u8, bits: u32) -> u8 {
    let modulo = 1u16 << bits;
    ((value as u16 + 1) % modulo) as u8
}

/// Whether `current` directly follows `previous` on a rolling counter of `bits` bits.
#[inline]
pub const fn counter_follows(previous: u8, current: u8, bits: u32) -> bool {
    next_counter(previous, bits) == current
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn rounds_half_away_from_zero() {
        assert_eq!(round_half_away(0.5), 1);
        assert_eq!(round_half_away(-0.5), -1);
        assert_eq!(round_half_away(1.4999), 1);
        assert_eq!(round_half_away(-2.5), -3);
        // -8.99 with factor 0.02 and offset -9 is the tie 0.5 in decimal, 0.49999999999996 in doubles.
        assert_eq!(round_half_away((-8.99 - -9.0) / 0.02), 1);
    }

    #[test]
    fn rounds_doubles_from_two_to_the_52_as_they_are() {
        // Adding 0.5 to 2^52 + 1 would round to even (2^52 + 2).
        assert_eq!(
            round_half_away(4_503_599_627_370_497.0),
            4_503_599_627_370_497
        );
        assert_eq!(
            round_half_away(-4_503_599_627_370_497.0),
            -4_503_599_627_370_497
        );
        assert_eq!(
            round_half_away(4_503_599_627_370_495.5),
            4_503_599_627_370_496
        );
        assert_eq!(round_half_away(-9_223_372_036_854_775_808.0), i64::MIN);
    }

    #[test]
    fn range_checks_are_exact_beyond_two_to_the_53() {
        // A 64-bit signed field: 2^63 does not fit although `i64::MAX as f64` is 2^63.
        let scale = Scale {
            factor: 1.0,
            offset: 0.5,
            check_min: -1e19,
            check_max: 1e19,
            raw_min: i64::MIN,
            raw_max: i64::MAX,
            type_min: i64::MIN,
            type_max: i64::MAX,
        };
        assert_eq!(to_raw(9_223_372_036_854_775_808.5, &scale, &[]), None);
        assert_eq!(
            to_raw(-9_223_372_036_854_775_807.5, &scale, &[]),
            Some(i64::MIN)
        );
        let wide = ScaleU64 {
            factor: 2.0,
            offset: 0.0,
            check_min: -1.0,
            check_max: 4e19,
            raw_min: 0,
            raw_max: u64::MAX,
        };
        assert_eq!(to_raw_u64(36_893_488_147_419_103_232.0, &wide, &[]), None); // 2^64 × 2
        assert_eq!(
            to_raw_u64(36_893_488_147_419_099_136.0, &wide, &[]),
            Some(18_446_744_073_709_549_568)
        );
        assert_eq!(to_raw_u64(1.0, &wide, &[]), Some(1)); // the tie 0.5 rounds away from zero
        assert_eq!(to_raw_u64(-1.0, &wide, &[]), None); // q = -0.5 rounds to -1
        assert_eq!(to_raw_u64(-0.999_999_98, &wide, &[]), Some(0)); // q = -0.49999999 rounds to 0
        assert_eq!(to_raw_u64(-1e-10, &wide, &[]), Some(0));
        assert_eq!(to_raw_u64(f64::NAN, &wide, &[]), None);
    }

    #[test]
    fn the_field_check_is_the_rounding_landing_in_the_field() {
        // 15 bits signed, factor 0.01, offset -5: the double quotient of the field's largest
        // value 158.83 is 16383.000000000002, a hair beyond the field, and rounds into it; a
        // special value outside the documented range passes while its quotient rounds to it.
        // (Expected values: ir/encoding.py fits_runtime and to_raw_runtime.)
        let scale = Scale {
            factor: 0.01,
            offset: -5.0,
            check_min: -168.84,
            check_max: 158.83,
            raw_min: -16384,
            raw_max: 16383,
            type_min: -16384,
            type_max: 16383,
        };
        assert_eq!(to_raw(158.83, &scale, &[]), Some(16383));
        assert_eq!(to_raw(-168.84, &scale, &[]), Some(-16384));
        assert_eq!(to_raw(158.834, &scale, &[16383]), Some(16383)); // q = 16383.4 rounds in
        assert_eq!(to_raw(158.835, &scale, &[16383]), None); // half a step beyond rounds out of it
        assert_eq!(to_raw(-168.844, &scale, &[-16384]), Some(-16384));
        assert_eq!(to_raw(-168.845, &scale, &[-16384]), None);
        // 48 bits, factor 1e-6, offset -0.05: the decoded double of raw 2^48 - 1 (a special
        // value) divides to 281474976710655.03 and encodes back; the next decimal does not.
        let wide = Scale {
            factor: 1e-6,
            offset: -0.05,
            check_min: -0.049_848_000_000_001,
            check_max: 281_474_976.660_249,
            raw_min: 152,
            raw_max: 0xFFFF_FFFF_FE69,
            type_min: 0,
            type_max: 0xFFFF_FFFF_FFFF,
        };
        let special = [0xFFFF_FFFF_FFFF];
        assert_eq!(
            to_raw(281_474_976.660_655, &wide, &special),
            Some(0xFFFF_FFFF_FFFF)
        );
        assert_eq!(to_raw(281_474_976.660_655_5, &wide, &special), None);
    }

    #[test]
    fn floor_matches_std() {
        for t in [
            -3.5,
            -3.0,
            -2.9999,
            -0.5,
            -0.0,
            0.0,
            0.25,
            0.5,
            1.0,
            1.5,
            2.5,
            7.999_999,
            1e15 + 0.5,
            -1e15 - 0.5,
            4.5e15,
            2_251_799_813_685_247.5,
            2_251_799_813_685_248.0,
        ] {
            assert_eq!(floor_i64(t), t.floor() as i64, "floor({t})");
        }
    }

    #[test]
    fn xor_folds_every_byte() {
        assert_eq!(xor_bytes(0x0102_0408_1020_4080), 0xFF);
        assert_eq!(xor_bytes(0xAA00_0000_0000_00AA), 0);
        assert_eq!(xor_bytes(0x0000_0000_0000_0100), 1);
    }

    #[test]
    fn to_raw_applies_the_range_rules() {
        let scale = Scale {
            factor: 0.02,
            offset: -9.0,
            check_min: -9.0,
            check_max: 3.6,
            raw_min: 0,
            raw_max: 630,
            type_min: 0,
            type_max: 1023,
        };
        assert_eq!(to_raw(-8.99, &scale, &[]), Some(1)); // decimal tie rounds away from zero
        assert_eq!(to_raw(3.6, &scale, &[]), Some(630));
        assert_eq!(to_raw(3.62, &scale, &[]), None); // outside the documented range
        assert_eq!(to_raw(-9.02, &scale, &[]), None); // below the field
        assert_eq!(to_raw(f64::NAN, &scale, &[]), None);
        assert_eq!(to_raw(f64::INFINITY, &scale, &[]), None);
        assert_eq!(to_raw(11.46, &scale, &[1023]), Some(1023)); // a special value passes
    }

    #[test]
    fn integer_rule_matches_the_double_rule() {
        // max_angular_speed: factor 2, 0..512 deg/s, raw 0 = no limit.
        let scale = IntScale {
            factor: 2,
            offset: 0,
            check_min: 0,
            check_max: 512,
            raw_min: 0,
            raw_max: 255,
            type_min: 0,
            type_max: 255,
        };
        let float = Scale {
            factor: 2.0,
            offset: 0.0,
            check_min: 0.0,
            check_max: 512.0,
            raw_min: 0,
            raw_max: 255,
            type_min: 0,
            type_max: 255,
        };
        for value in -5..=520 {
            assert_eq!(
                to_raw_int(value, &scale, &[0]),
                to_raw(value as f64, &float, &[0]),
                "{value}"
            );
        }
        // battery temperature: offset -40.
        let scale = IntScale {
            factor: 1,
            offset: -40,
            check_min: -40,
            check_max: 215,
            raw_min: 0,
            raw_max: 255,
            type_min: 0,
            type_max: 255,
        };
        let float = Scale {
            factor: 1.0,
            offset: -40.0,
            check_min: -40.0,
            check_max: 215.0,
            raw_min: 0,
            raw_max: 255,
            type_min: 0,
            type_max: 255,
        };
        for value in -300..=300 {
            assert_eq!(
                to_raw_int(value, &scale, &[]),
                to_raw(value as f64, &float, &[]),
                "{value}"
            );
        }
    }

    #[test]
    fn floor_matches_std_on_a_million_doubles() {
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        for i in 0..1_000_000u32 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            // Magnitudes from 2^-10 to 2^60 with random mantissas, half of them negative.
            let exponent = 1013 + (state >> 58) % 70;
            let t = f64::from_bits((exponent << 52) | (state & 0x000F_FFFF_FFFF_FFFF));
            let t = if i % 2 == 0 { t } else { -t };
            assert_eq!(floor_i64(t), t.floor() as i64, "floor({t})");
        }
    }

    #[test]
    fn reciprocal_path_matches_the_division() {
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        for (factor, offset, max) in [
            (0.2, 0.0, 800.0),
            (0.02, -500.0, 800.0),
            (0.1, -1080.0, 1080.0),
            (0.05, 0.0, 100.0),
            (0.001, 0.0, 65.535),
            (0.5, 0.0, 125.0),
            (0.4, 0.0, 100.0),
            (0.003, 0.0, 12.0),
            (0.01, -40.0, 600.0),
        ] {
            // From the tie epsilon below the field's 0, which the field check lets through.
            let low = offset - factor * TIE_EPSILON;
            let scale = Scale {
                factor,
                offset,
                check_min: low,
                check_max: max,
                raw_min: 0,
                raw_max: i64::MAX,
                type_min: 0,
                type_max: i64::MAX,
            };
            let reciprocal = 1.0 / factor;
            for x in [low, (offset + low) / 2.0, offset] {
                assert_eq!(
                    to_raw_documented_unsigned_recip(x, &scale, reciprocal),
                    Some(0),
                    "{factor} {x}"
                );
                assert_eq!(
                    to_raw_documented_unsigned(x, &scale),
                    Some(0),
                    "{factor} {x}"
                );
            }
            let steps = ((max - offset) / factor) as i64;
            for raw in 0..=steps {
                // Every raw step, its decimal tie, and values around both.
                for x in [
                    raw as f64 * factor + offset,
                    (raw as f64 + 0.5) * factor + offset,
                    raw as f64 * factor + offset + factor * 0.4999,
                    raw as f64 * factor + offset + factor * 0.5001,
                ] {
                    assert_eq!(
                        to_raw_documented_unsigned_recip(x, &scale, reciprocal),
                        to_raw_documented_unsigned(x, &scale),
                        "{factor} {x}"
                    );
                }
            }
            for _ in 0..200_000 {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let x = offset + (state >> 11) as f64 / (1u64 << 53) as f64 * (max - offset);
                assert_eq!(
                    to_raw_documented_unsigned_recip(x, &scale, reciprocal),
                    to_raw_documented_unsigned(x, &scale),
                    "{factor} {x}"
                );
            }
        }
    }

    #[test]
    fn counters_wrap() {
        assert_eq!(next_counter(15, 4), 0);
        assert_eq!(next_counter(255, 8), 0);
        assert_eq!(next_counter(7, 4), 8);
        assert!(counter_follows(255, 0, 8));
        assert!(!counter_follows(3, 5, 4));
    }
}
