//! Seeds of every random choice, derived from (global seed, scene, task, split, index), so a
//! choice never depends on what else is generated, in which order, or on which thread.

/// Mix `parts` into `global` (SplitMix64 finaliser after each part).
pub fn derive_seed(global: u64, parts: &[u64]) -> u64 {
    let mut z = mix(global ^ 0x7C15_9E37_79B9_7F4A);
    for &p in parts {
        z = mix(z ^ p.wrapping_mul(0xD1B5_4A32_D192_ED03));
    }
    z
}

fn mix(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::derive_seed;

    #[test]
    fn parts_and_order_matter() {
        let a = derive_seed(1, &[2, 3]);
        assert_eq!(a, derive_seed(1, &[2, 3]));
        assert_ne!(a, derive_seed(1, &[3, 2]));
        assert_ne!(a, derive_seed(2, &[2, 3]));
        assert_ne!(derive_seed(1, &[0]), derive_seed(1, &[]));
    }
}
