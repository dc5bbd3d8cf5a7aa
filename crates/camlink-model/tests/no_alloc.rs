//! No allocation in the time loop: 1,000 kinematic steps and 1,000 dynamic
//! steps of each benchmark model, after the first, allocate nothing; nor
//! do those of a run with unilateral contacts between its events; nor do
//! rows at output times between step ends (`issue27_rows_between_step_ends_*`).
//!
//! A counting global allocator counts the allocations made on the thread
//! that runs the analysis while counting is switched on; the sink switches
//! it on at the first row after the start and off at the last, so the
//! count covers the steps, their output rows and the warnings path, and
//! not the set-up.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;

use camlink_core::dynamics::integrator::{self, Settings as DynSettings};
use camlink_core::kinematics;
use camlink_core::run::PointOutput;
use camlink_core::run::{time_grid, Channel, Settings, Sink, Stop};
use camlink_core::Model;

use camlink_testkit::mechanisms;

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

/// The system allocator, counting allocations on threads that count.
struct Counting;

impl Counting {
    fn note() {
        // `try_with`: the thread-local may be gone while a thread exits.
        let counting = COUNTING.try_with(Cell::get).unwrap_or(false);
        if counting {
            let _ = COUNT.try_with(|c| c.set(c.get() + 1));
        }
    }
}

// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        Self::note();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        Self::note();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        Self::note();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Counts allocations from row `first` to row `last` (0-based).
struct Window {
    first: usize,
    last: usize,
    rows: usize,
}

impl Sink for Window {
    fn begin(&mut self, _: &[Channel]) {}
    fn row(&mut self, _: f64, _: &[f64]) -> Result<(), Stop> {
        if self.rows == self.first {
            COUNT.with(|c| c.set(0));
            COUNTING.with(|c| c.set(true));
        }
        if self.rows == self.last {
            COUNTING.with(|c| c.set(false));
        }
        self.rows += 1;
        Ok(())
    }
}

const STEPS: usize = 1000;

/// Allocations of steps 2 … 1,001 of a run over 1,002 times of 1 ms
/// (the analysis fills every output row, as a user's run does).
fn allocations(run: impl FnOnce(&[f64], &mut Window)) -> usize {
    let times = time_grid((STEPS + 1) as f64 * 1e-3, 1e-3).unwrap();
    assert_eq!(times.len(), STEPS + 2);
    let mut sink = Window {
        first: 1,
        last: STEPS + 1,
        rows: 0,
    };
    run(&times, &mut sink);
    assert_eq!(sink.rows, STEPS + 2, "the run stopped early");
    COUNTING.with(|c| c.set(false));
    COUNT.with(Cell::get)
}

fn example(file: &str) -> camlink_model::Loaded {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(file);
    camlink_model::load_path(&path).unwrap()
}

/// Every named point of every body of `model`, as output channels.
fn all_points(model: &Model) -> Vec<PointOutput> {
    model
        .bodies
        .iter()
        .flat_map(|b| {
            b.points
                .iter()
                .map(move |p| format!("{}.{}", b.name, p.name))
        })
        .map(|full| PointOutput::named(model, &full).unwrap())
        .collect()
}

fn kinematic_allocations(file: &str) -> usize {
    let loaded = example(file);
    let settings = Settings {
        tol: loaded.analysis.tol,
        max_iter: loaded.analysis.max_iter,
        jerk: false,
    };
    let points = all_points(&loaded.model);
    allocations(|times, sink| {
        kinematics::run(&loaded.model, times, &settings, &points, sink).unwrap();
    })
}

fn dynamic_allocations(model: &Model, points: &[PointOutput]) -> usize {
    dynamic_allocations_at_step(model, points, 1e-3)
}

/// [`dynamic_allocations`] with steps of `h` (s): at h = 0.7 ms most
/// output times (every 1 ms) lie between step ends, and their rows come
/// from the interpolated state, projected onto the constraints.
fn dynamic_allocations_at_step(model: &Model, points: &[PointOutput], h: f64) -> usize {
    let settings = DynSettings {
        step: h,
        ..DynSettings::default()
    };
    allocations(|times, sink| {
        integrator::run(model, times, &settings, points, sink).unwrap();
    })
}

#[test]
fn four_bar_kinematics_allocates_nothing_per_step() {
    assert_eq!(kinematic_allocations("four_bar.toml"), 0);
}

#[test]
fn cam_roller_kinematics_allocates_nothing_per_step() {
    assert_eq!(kinematic_allocations("cam_seed_example_3_4_3.toml"), 0);
}

#[test]
fn slider_crank_dynamics_allocates_nothing_per_step() {
    let model = mechanisms::slider_crank(0.3, 10.0, false);
    assert_eq!(dynamic_allocations(&model, &[]), 0);
}

#[test]
fn chain_dynamics_allocates_nothing_per_step() {
    assert_eq!(dynamic_allocations(&mechanisms::chain(10, 0.1), &[]), 0);
}

#[test]
fn slider_crank_example_dynamics_allocates_nothing_per_step() {
    let loaded = example("dyn_slider_crank.toml");
    assert_eq!(
        dynamic_allocations(&loaded.model, &all_points(&loaded.model)),
        0
    );
}

/// 150 coordinates: the sparse LU's path.
#[test]
fn driven_chain_kinematics_allocates_nothing_per_step() {
    let model = mechanisms::driven_chain(50, 0.1);
    let n = allocations(|times, sink| {
        kinematics::run(&model, times, &Settings::default(), &[], sink).unwrap();
    });
    assert_eq!(n, 0);
}

/// 250 unknowns in the augmented matrix: the sparse LU's path.
#[test]
fn long_chain_dynamics_allocates_nothing_per_step() {
    assert_eq!(dynamic_allocations(&mechanisms::chain(50, 0.1), &[]), 0);
}

/// `tests/no_alloc/ball_over_floor.toml` with the text `from` replaced by
/// `to` in each pair.
fn ball_over_floor(edits: &[(&str, &str)]) -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/no_alloc/ball_over_floor.toml");
    let mut text = std::fs::read_to_string(path).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "no {from:?} in the ball model");
        text = text.replace(from, to);
    }
    camlink_model::load_str(&text, camlink_model::Format::Toml, "ball_over_floor.toml")
        .unwrap()
        .model
}

/// The valve-jump example below its jump speed: the unilateral contact
/// stays closed and its normal force is watched at every step.
#[test]
fn closed_unilateral_contact_dynamics_allocates_nothing_per_step() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/cam_valve_jump.toml");
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains("rpm = 6000 "), "the example's speed moved");
    let text = text.replace("rpm = 6000 ", "rpm = 600 ");
    let loaded = camlink_model::load_str(&text, camlink_model::Format::Toml, "valve.toml").unwrap();
    assert_eq!(
        dynamic_allocations(&loaded.model, &all_points(&loaded.model)),
        0
    );
}

/// A ball falling for a second from 10 m: the contact open throughout,
/// its gap watched and the rows' energy and drift those of the model
/// without the contact (the guide's two equations).
#[test]
fn open_unilateral_contact_dynamics_allocates_nothing_per_step() {
    let model = ball_over_floor(&[]);
    assert_eq!(dynamic_allocations(&model, &[]), 0);
}

/// A ball settling on a compliant (Hunt–Crossley) floor, its force one of
/// the model's.
#[test]
fn compliant_contact_dynamics_allocates_nothing_per_step() {
    let model = ball_over_floor(&[
        ("position = [0, 10]", "position = [0, 0.1]"),
        (
            "restitution = 0.5",
            "stiffness = 1e5\nexponent = 1.5\ndamping = 0.2",
        ),
    ]);
    assert_eq!(dynamic_allocations(&model, &[]), 0);
}

/// Output times between step ends: a step of 0.7 ms against rows every
/// 1 ms, so that most rows are interpolated inside a step, projected onto
/// the constraints and given their consistent q̈ and λ.
const BETWEEN: f64 = 7e-4;

#[test]
fn issue27_rows_between_step_ends_allocate_nothing_slider_crank() {
    let model = mechanisms::slider_crank(0.3, 10.0, false);
    assert_eq!(dynamic_allocations_at_step(&model, &[], BETWEEN), 0);
}

/// 250 unknowns: the sparse LU's path, in the interpolated rows' own
/// matrix too.
#[test]
fn issue27_rows_between_step_ends_allocate_nothing_long_chain() {
    let model = mechanisms::chain(50, 0.1);
    assert_eq!(dynamic_allocations_at_step(&model, &[], BETWEEN), 0);
}

#[test]
fn issue27_rows_between_step_ends_allocate_nothing_example_points() {
    let loaded = example("dyn_slider_crank.toml");
    let points = all_points(&loaded.model);
    assert_eq!(
        dynamic_allocations_at_step(&loaded.model, &points, BETWEEN),
        0
    );
}

/// The open contact's rows between step ends come from the step's two
/// snapshots.
#[test]
fn issue27_rows_between_step_ends_allocate_nothing_open_contact() {
    let model = ball_over_floor(&[]);
    assert_eq!(dynamic_allocations_at_step(&model, &[], BETWEEN), 0);
}

/// The closed contact's rows between step ends, its normal force from
/// the interpolated state's multipliers.
#[test]
fn issue27_rows_between_step_ends_allocate_nothing_closed_contact() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/cam_valve_jump.toml");
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains("rpm = 6000 "), "the example's speed moved");
    let text = text.replace("rpm = 6000 ", "rpm = 600 ");
    let loaded = camlink_model::load_str(&text, camlink_model::Format::Toml, "valve.toml").unwrap();
    let points = all_points(&loaded.model);
    assert_eq!(
        dynamic_allocations_at_step(&loaded.model, &points, BETWEEN),
        0
    );
}
