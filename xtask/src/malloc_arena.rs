//! One glibc malloc arena for an evaluation, and its freed memory given back as it runs
//! ([`Trimmer`]).
//!
//! glibc gives each thread that allocates its own arena (up to eight per core). An evaluation's
//! workers each load homes of several megabytes into their own arena, and the holes a home
//! leaves in one arena serve only that worker: over a split of many homes, the process keeps
//! more and more memory it no longer uses. With one arena the workers reuse each other's
//! holes. Measured on the `vlnverse` preset (two workers): coarse test 176 -> 156 MB peak, coarse
//! train 244 -> 186 MB, 1-2% more time (docs/vec-env-performance.md).
//!
//! glibc reads the setting from `MALLOC_ARENA_MAX` when the process starts, so the process
//! sets it and executes itself again (same process id, same arguments): safe Rust, no new
//! dependency. A value the user set is kept; elsewhere than Linux with glibc this does nothing.

/// The environment variable glibc reads its arena limit from.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const VAR: &str = "MALLOC_ARENA_MAX";

/// Executes this binary again with `MALLOC_ARENA_MAX=1` unless the variable is set (by the
/// user, or by the execution before); returns only when it does not (the variable was set,
/// or the execution failed: the run then goes on with glibc's default).
pub fn one_arena() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use std::os::unix::process::CommandExt;
        if let Some(v) = std::env::var_os(VAR) {
            tracing::debug!("glibc malloc arenas: {VAR}={}", v.to_string_lossy());
            return;
        }
        if std::env::var_os("GLIBC_TUNABLES").is_some() {
            tracing::debug!("glibc malloc arenas: as GLIBC_TUNABLES sets them");
            return;
        }
        let Ok(exe) = std::env::current_exe() else {
            return;
        };
        let err = std::process::Command::new(exe)
            .args(std::env::args_os().skip(1))
            .env(VAR, "1")
            .exec();
        tracing::debug!("running with glibc's default arenas: could not execute again: {err}");
    }
}

/// How often [`Trimmer`] gives freed memory back. When it was chosen (the eighth pass of
/// docs/vec-env-performance.md, before runs went home by home), coarse test and train of the
/// `vlnverse` preset peaked at 120.5 and 132.8 MB at 250 ms, against 124.5 and 149.2 MB
/// untrimmed (1 s: 119.4 and 135.4), and a 1,200-episode sample took the same time.
pub const TRIM_PERIOD: std::time::Duration = std::time::Duration::from_millis(250);

/// Gives the memory glibc keeps after it was freed back to the system, every [`TRIM_PERIOD`]
/// until dropped (a thread of its own). glibc returns freed memory only from the top of its
/// heap: the holes homes leave below live data stay resident, so an evaluation's resident size
/// rises in steps with every home it visits, although its live heap does not. `malloc_trim(0)`
/// releases those pages (they come back, zeroed, when reused). Elsewhere than Linux with glibc
/// it does nothing.
pub struct Trimmer {
    stop: Option<std::sync::mpsc::Sender<()>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Trimmer {
    /// Start trimming every `period`.
    pub fn start(period: std::time::Duration) -> Trimmer {
        if !cfg!(all(target_os = "linux", target_env = "gnu")) {
            return Trimmer {
                stop: None,
                thread: None,
            };
        }
        let (stop, stopped) = std::sync::mpsc::channel::<()>();
        let thread = std::thread::Builder::new()
            .name("malloc-trim".into())
            .spawn(move || {
                while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
                    stopped.recv_timeout(period)
                {
                    release_freed();
                }
            })
            .ok();
        Trimmer {
            stop: Some(stop),
            thread,
        }
    }
}

impl Drop for Trimmer {
    fn drop(&mut self) {
        drop(self.stop.take());
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// glibc's `malloc_trim(0)`: every arena's free pages given back.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)] // a foreign function; see the SAFETY note
fn release_freed() {
    extern "C" {
        fn malloc_trim(pad: usize) -> std::ffi::c_int;
    }
    // SAFETY: `malloc_trim` takes no pointer and touches only the allocator's own state, under
    // the allocator's locks; any thread may call it at any time.
    unsafe {
        malloc_trim(0);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn release_freed() {}

#[cfg(all(test, target_os = "linux", target_env = "gnu"))]
mod tests {
    use super::*;

    /// Resident bytes of this process (`VmRSS`).
    fn resident() -> usize {
        let status = std::fs::read_to_string("/proc/self/status").expect("status");
        let kb: usize = status
            .lines()
            .find_map(|l| l.strip_prefix("VmRSS:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
            .expect("VmRSS");
        kb * 1024
    }

    /// Memory freed below a live allocation stays resident until trimmed, then goes; and a
    /// trimmer stops when dropped, however long its period.
    #[test]
    fn freed_memory_below_live_data_goes_back_when_trimmed() {
        const BLOCK: usize = 64 << 10;
        const MB: usize = 48;
        let mut blocks: Vec<Vec<u8>> = (0..MB * (1 << 20) / BLOCK)
            .map(|i| vec![i as u8 | 1; BLOCK])
            .collect();
        let last = blocks.pop().expect("blocks");
        drop(blocks);
        let before = resident();
        release_freed();
        let after = resident();
        assert!(
            before > after + ((MB / 2) << 20),
            "resident {before} bytes before the trim, {after} after"
        );
        assert_eq!(std::hint::black_box(&last)[BLOCK - 1], 0xff);
        drop(Trimmer::start(std::time::Duration::from_secs(3600)));
    }
}
