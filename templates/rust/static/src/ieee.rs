//! IEEE 754 fields: the physical value is the float the field's bit pattern holds. Encoding is the
//! shared rule: a finite value must lie in the field's range, NaN and ±Infinity pass only where no
//! range is documented, and NaN is sent as the format's quiet NaN with its sign (another payload
//! decodes as NaN but is never produced).

/// The bit pattern of a float32 field holding `value`: `None` when the rule refuses it (`min` and
/// `max` are the range's float32 bounds; `ranged`: the range is documented).
#[inline(always)]
pub fn f32_bits(value: f32, min: f32, max: f32, ranged: bool) -> Option<u32> {
    if value.is_nan() {
        return (!ranged).then_some(0x7FC0_0000 | (value.to_bits() & 0x8000_0000));
    }
    ((min..=max).contains(&value) || (value.is_infinite() && !ranged)).then_some(value.to_bits())
}

/// The bit pattern of a float64 field holding `value` (see [`f32_bits`]).
#[inline(always)]
pub fn f64_bits(value: f64, min: f64, max: f64, ranged: bool) -> Option<u64> {
    if value.is_nan() {
        return (!ranged).then_some(0x7FF8_0000_0000_0000 | (value.to_bits() & 0x8000_0000_0000_0000));
    }
    ((min..=max).contains(&value) || (value.is_infinite() && !ranged)).then_some(value.to_bits())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_and_infinity_pass_only_without_a_range() {
        assert_eq!(f32_bits(f32::NAN, f32::MIN, f32::MAX, false), Some(0x7FC0_0000));
        assert_eq!(f32_bits(-f32::NAN, f32::MIN, f32::MAX, false), Some(0xFFC0_0000));
        assert_eq!(f32_bits(f32::from_bits(0x7F80_0001), f32::MIN, f32::MAX, false), Some(0x7FC0_0000));
        assert_eq!(f32_bits(f32::INFINITY, 0.0, 250.0, true), None);
        assert_eq!(f32_bits(f32::NEG_INFINITY, f32::MIN, f32::MAX, false), Some(0xFF80_0000));
        assert_eq!(f64_bits(f64::NAN, 0.0, 1.0, true), None);
        assert_eq!(f64_bits(f64::NAN, f64::MIN, f64::MAX, false), Some(0x7FF8_0000_0000_0000));
    }

    #[test]
    fn finite_values_must_lie_in_the_range() {
        assert_eq!(f32_bits(250.0, 0.0, 250.0, true), Some(250f32.to_bits()));
        assert_eq!(f32_bits(250.00002, 0.0, 250.0, true), None);
        assert_eq!(f32_bits(-0.0, 0.0, 250.0, true), Some(0x8000_0000));
        assert_eq!(f64_bits(-1e-300, 0.0, 1e6, true), None);
        assert_eq!(f64_bits(f64::MAX, f64::MIN, f64::MAX, false), Some(f64::MAX.to_bits()));
    }
}
