//! Progress of long stages (attachment test, motion test, dictionary build), reported to a
//! process-wide sink the way `log` reports messages: the library only counts, a front end
//! (the CLI's progress bars) draws. Without a sink nothing happens.

use std::sync::OnceLock;

/// Receives progress. Called from worker threads, hence `Sync`.
pub trait Progress: Send + Sync {
    /// A stage of `total` steps begins (e.g. `attachment C2`, `motion test 3`).
    fn begin(&self, stage: &str, total: u64);
    /// `steps` more steps of the current stage are done.
    fn advance(&self, steps: u64);
    /// The current stage is over.
    fn end(&self);
    /// A line on how a long run goes, between stages (e.g. each box a range design tried).
    fn note(&self, line: &str);
}

static SINK: OnceLock<Box<dyn Progress>> = OnceLock::new();

/// Installs the process's sink; `false` when one was installed before (it stays).
pub fn set_sink(sink: Box<dyn Progress>) -> bool {
    SINK.set(sink).is_ok()
}

/// A stage begins.
pub fn begin(stage: &str, total: u64) {
    if let Some(sink) = SINK.get() {
        sink.begin(stage, total);
    }
}

/// Steps done.
pub fn advance(steps: u64) {
    if let Some(sink) = SINK.get() {
        sink.advance(steps);
    }
}

/// The stage ends.
pub fn end() {
    if let Some(sink) = SINK.get() {
        sink.end();
    }
}

/// A line on how a long run goes.
pub fn note(line: &str) {
    if let Some(sink) = SINK.get() {
        sink.note(line);
    }
}

/// Whether anything receives progress: a run may skip measuring what only a note would say.
pub fn listening() -> bool {
    SINK.get().is_some()
}
