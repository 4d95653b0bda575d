//! Which copy of the rasteriser's fill and resolve runs on this CPU.
//!
//! The fill and the resolve are plain loops the compiler vectorises. Built for the x86-64
//! baseline they get 4-wide SSE2; a second copy built with AVX2 (8 lanes; with BMI1/2, LZCNT
//! and POPCNT: x86-64-v3's features but FMA, F16C and MOVBE) is ~20% faster a frame. The copy
//! is chosen at the first frame, so one build runs on any x86-64 CPU. Both copies give the
//! same pixels: Rust never fuses a multiply and an add on its own, FMA is not enabled, and a
//! lane of an 8-wide operation computes what a lane of a 4-wide one does.

use std::sync::OnceLock;

/// Environment variable: `baseline` runs the baseline copy on a CPU that has the AVX2 one
/// (to compare them); anything else, or unset, runs the widest copy the CPU has.
pub const ISA_VAR: &str = "VLNVERSE_RASTER_ISA";

/// Which copy of the fill and resolve this process runs, `avx2` or `baseline` (see
/// [`ISA_VAR`]); for benchmarks to print beside their figures.
pub fn copy_in_use() -> &'static str {
    Isa::detect().name()
}

/// Proof that this CPU has the AVX2 copy's features: only [`Isa::widest`] makes one, after
/// checking them, so an [`Isa::Avx2`] cannot be written anywhere else.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Detected(());

/// A copy of the fill and resolve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Isa {
    /// Built for the target as configured (SSE2 on x86-64).
    Baseline,
    /// Built with AVX2, BMI1/2, LZCNT and POPCNT: CPUs since about 2013-2015.
    #[cfg(target_arch = "x86_64")]
    Avx2(Detected),
}

impl Isa {
    /// The widest copy this CPU runs, unless [`ISA_VAR`] says `baseline`; decided once.
    pub(super) fn detect() -> Isa {
        static CHOSEN: OnceLock<Isa> = OnceLock::new();
        *CHOSEN.get_or_init(|| Isa::choose(std::env::var(ISA_VAR).ok().as_deref(), Isa::widest()))
    }

    /// The copy to run given [`ISA_VAR`]'s value and the widest copy the CPU runs: `baseline`
    /// (any case, spaces around it ignored) forces the baseline, anything else takes the widest.
    fn choose(var: Option<&str>, widest: Option<Isa>) -> Isa {
        let baseline = var.is_some_and(|v| v.trim().eq_ignore_ascii_case("baseline"));
        match widest {
            Some(isa) if !baseline => isa,
            _ => Isa::Baseline,
        }
    }

    /// A short name: `avx2` or `baseline`.
    pub(super) fn name(self) -> &'static str {
        match self {
            Isa::Baseline => "baseline",
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2(_) => "avx2",
        }
    }

    /// The AVX2 copy when this CPU can run it.
    pub(super) fn widest() -> Option<Isa> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("bmi1")
            && std::arch::is_x86_feature_detected!("bmi2")
            && std::arch::is_x86_feature_detected!("lzcnt")
            && std::arch::is_x86_feature_detected!("popcnt")
        {
            return Some(Isa::Avx2(Detected(())));
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::Isa;

    #[test]
    fn the_variable_forces_the_baseline_and_otherwise_the_widest_copy_runs() {
        let wide = Isa::widest();
        assert_eq!(Isa::choose(Some("baseline"), wide), Isa::Baseline);
        assert_eq!(Isa::choose(Some(" Baseline\n"), wide), Isa::Baseline);
        assert_eq!(Isa::choose(None, None), Isa::Baseline);
        assert_eq!(Isa::choose(Some("avx2"), None), Isa::Baseline);
        if let Some(wide) = wide {
            assert_eq!(Isa::choose(None, Some(wide)), wide);
            assert_eq!(Isa::choose(Some("auto"), Some(wide)), wide);
            assert_eq!(Isa::choose(Some(""), Some(wide)), wide);
            assert_eq!(wide.name(), "avx2");
        }
        assert_eq!(Isa::Baseline.name(), "baseline");
    }
}
