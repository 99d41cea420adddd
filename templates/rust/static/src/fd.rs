//! CAN FD frames (up to 64 bytes), held as their bytes: a field is read from the bytes from its
//! first byte as one integer (8 bytes, 16 for a field over 9 bytes) in its own byte order, and
//! written back the same way.

/// `W` bytes of `bytes` from `at`, zero beyond its end.
#[inline(always)]
pub fn window<const W: usize>(bytes: &[u8], at: usize) -> [u8; W] {
    let mut out = [0u8; W];
    let end = bytes.len().min(at + W);
    out[..end - at].copy_from_slice(&bytes[at..end]);
    out
}

/// Write a window back from `at` (its bytes beyond the end of `bytes` are dropped).
#[inline(always)]
pub fn put_window<const W: usize>(bytes: &mut [u8], at: usize, window: [u8; W]) {
    let end = bytes.len().min(at + W);
    bytes[at..end].copy_from_slice(&window[..end - at]);
}

/// XOR of all bytes.
#[inline(always)]
pub fn xor(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0, |x, &b| x ^ b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_stop_at_the_frame_end() {
        let mut frame = [0u8; 12];
        for (i, b) in frame.iter_mut().enumerate() {
            *b = i as u8 + 1;
        }
        assert_eq!(window::<8>(&frame, 8), [9, 10, 11, 12, 0, 0, 0, 0]);
        put_window(&mut frame, 8, [0xA0u8, 0xA1, 0xA2, 0xA3, 0xA4, 0xA5, 0xA6, 0xA7]);
        assert_eq!(frame[8..], [0xA0, 0xA1, 0xA2, 0xA3]);
        assert_eq!(xor(&[1, 2, 4]), 7);
    }
}
