//! Progress of long steps: the CLI draws bars, libraries and tests pass [`NoProgress`].

/// Progress of long steps. `tick` may be called from worker threads.
pub trait Progress: Sync {
    /// A step with `total` units of work begins.
    fn start(&self, label: &str, total: u64);
    /// One unit is done.
    fn tick(&self);
    /// The step is done.
    fn finish(&self);
    /// A status line for the current step (e.g. iteration, blocks and E). Default: ignored.
    fn message(&self, _status: &str) {}
    /// Whether the caller wants the run stopped (e.g. Ctrl-C in Python). The runner checks
    /// it before it writes anything and again, under the output lock, before a finished
    /// run takes the place of the earlier output, so a stopped run leaves the earlier
    /// output whole ([`HotcutError::Cancelled`](crate::HotcutError::Cancelled)). Default:
    /// never.
    fn cancelled(&self) -> bool {
        false
    }
}

/// Reports nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn start(&self, _: &str, _: u64) {}
    fn tick(&self) {}
    fn finish(&self) {}
}
