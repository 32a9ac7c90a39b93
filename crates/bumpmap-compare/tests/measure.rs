//! `bumpmap_compare` as a library: what it measures, what it tells a `Progress`, what it refuses.

use std::cell::RefCell;

use bumpmap_compare::{CompareError, CompareNote, CompareOptions, Progress};

#[derive(Default)]
struct Told {
    start: RefCell<Option<u64>>,
    advanced: RefCell<Vec<u64>>,
    steps: RefCell<Vec<String>>,
    notes: RefCell<Vec<CompareNote>>,
    finished: RefCell<bool>,
}

impl Progress for Told {
    fn start(&self, steps: u64) {
        *self.start.borrow_mut() = Some(steps);
    }
    fn step(&self, what: &str) {
        self.steps.borrow_mut().push(what.to_string());
    }
    fn advance(&self, done: u64) {
        self.advanced.borrow_mut().push(done);
    }
    fn note(&self, note: &CompareNote) {
        self.notes.borrow_mut().push(note.clone());
    }
    fn finish(&self) {
        *self.finished.borrow_mut() = true;
    }
}

fn small(techniques: &[&str]) -> CompareOptions {
    CompareOptions {
        size: 32,
        spp: 4,
        techniques: techniques.iter().map(|t| t.to_string()).collect(),
        studies: Vec::new(),
        ..Default::default()
    }
}

#[test]
fn measures_the_techniques_asked_for_and_tells_each_step() {
    let told = Told::default();
    let (results, inputs) = bumpmap_compare::measure(&small(&["kilgard", "single-pass", "kilgrad"]), &told).unwrap();
    assert!(inputs.is_empty(), "the bricks preset is no file: {inputs:?}");
    let names: Vec<&str> = results.outcomes.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["kilgard", "single-pass", "kilgrad"]);
    for o in &results.outcomes[..2] {
        let r = o.result.as_ref().unwrap_or_else(|why| panic!("{} was skipped: {why}", o.name));
        // Both draw the lit torus the reference draws: far from it would be a broken pipeline,
        // equal to it impossible (8 bits against float, one sample against four).
        assert!(r.scores.psnr > 15.0 && r.scores.psnr.is_finite(), "{}: PSNR {}", o.name, r.scores.psnr);
        assert_eq!(r.image.width, 32);
    }
    assert!(results.outcomes[2].result.is_err(), "an unknown name is skipped");
    // Three techniques, the two references, convergence and the seven studies' places.
    assert_eq!(*told.start.borrow(), Some(3 + 10));
    assert_eq!(*told.advanced.borrow(), (1..=13).collect::<Vec<_>>());
    assert!(told.steps.borrow().iter().any(|s| s.starts_with("reference, 4 samples")), "{:?}", told.steps.borrow());
    assert!(*told.finished.borrow());
    assert!(
        matches!(told.notes.borrow().as_slice(), [CompareNote::Skipped { name, .. }] if name == "kilgrad"),
        "{:?}",
        told.notes.borrow()
    );
}

#[test]
fn refuses_before_any_work() {
    let mut o = small(&["kilgard", "kilgard"]);
    assert!(matches!(bumpmap_compare::measure(&o, &()), Err(CompareError::Twice(n)) if n == "kilgard"));
    o.techniques = vec!["kilgard".into()];
    o.bump_scale = -1.0;
    assert!(matches!(bumpmap_compare::measure(&o, &()), Err(CompareError::BumpScale(_))));
}
