//! FNV-1a, 64 bit: the one hash of the layer (the checksum of serialized FMU states; models may
//! use it for their own bytes, e.g. to bind a snapshot to its resource).

use std::hash::Hasher;

/// FNV-1a 64 of `bytes` (the `fnv` crate's hasher: offset basis 0xcbf29ce484222325, prime
/// 0x100000001b3).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h = fnv::FnvHasher::default();
    h.write(bytes);
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_vectors() {
        // test vectors of the FNV reference (isthe.com/chongo/tech/comp/fnv)
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }
}
