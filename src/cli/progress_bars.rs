//! The library's progress ([`cable_dict::progress`]) drawn as indicatif bars with an ETA on
//! standard error — only on a terminal (indicatif hides them on pipes), never with `--quiet`;
//! its notes (a long run's milestones) as lines on standard error, also on pipes.

use cable_dict::progress::{Progress, set_sink};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::Mutex;

/// One bar at a time: stages do not overlap.
struct Bars {
    bar: Mutex<Option<ProgressBar>>,
}

impl Progress for Bars {
    fn begin(&self, stage: &str, total: u64) {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
        if let Ok(style) =
            ProgressStyle::with_template("{msg:<18} {wide_bar} {pos}/{len} {elapsed} (ETA {eta})")
        {
            bar.set_style(style);
        }
        bar.set_message(stage.to_string());
        if let Ok(mut slot) = self.bar.lock() {
            *slot = Some(bar);
        }
    }

    fn advance(&self, steps: u64) {
        if let Ok(slot) = self.bar.lock()
            && let Some(bar) = slot.as_ref()
        {
            bar.inc(steps);
        }
    }

    fn end(&self) {
        if let Ok(mut slot) = self.bar.lock()
            && let Some(bar) = slot.take()
        {
            bar.finish_and_clear();
        }
    }

    fn note(&self, line: &str) {
        match self.bar.lock().ok().as_deref() {
            Some(Some(bar)) => bar.suspend(|| eprintln!("{line}")),
            _ => eprintln!("{line}"),
        }
    }
}

/// Draws progress bars from now on, unless `quiet`.
pub fn install(quiet: bool) {
    if !quiet {
        let _ = set_sink(Box::new(Bars {
            bar: Mutex::new(None),
        }));
    }
}
