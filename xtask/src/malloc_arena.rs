//! One glibc malloc arena for an evaluation.
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
