//! Progress on the command line: a bar on stderr. Warnings and notes are said through
//! `bumpmap_words::report`, re-exported here.

use indicatif::{ProgressBar, ProgressStyle};

pub use bumpmap_words::report::{note, warn};

/// How long work shows its progress.
#[derive(Clone, Default)]
pub enum Progress {
    /// Not at all.
    #[default]
    Hidden,
    /// A bar on stderr (where stderr is a terminal).
    Bar,
}

/// Counted steps of long work: a bar on stderr for [`Progress::Bar`], or nothing.
pub struct Steps {
    bar: ProgressBar,
}

impl Steps {
    /// `total` steps, shown as `progress` says, the bar in `template` (indicatif's).
    pub fn new(progress: &Progress, total: u64, template: &str) -> Self {
        let bar = match progress {
            Progress::Bar => ProgressBar::new(total),
            Progress::Hidden => ProgressBar::hidden(),
        };
        let bar = bar.with_style(ProgressStyle::with_template(template).expect("a valid template"));
        bar.set_length(total);
        Self { bar }
    }

    /// One more step done.
    pub fn inc(&self) {
        self.bar.inc(1);
    }

    /// What is being done now, beside the bar.
    pub fn set_message(&self, message: impl Into<String>) {
        self.bar.set_message(message.into());
    }

    /// Runs `f` with the bar hidden, for a line on stderr.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
