//! A steady-state step allocates nothing: every integrator owns its buffers.
#![allow(unsafe_code)] // a counting global allocator needs `unsafe impl`

use std::alloc::{GlobalAlloc, Layout, System as SystemAllocator};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use hooke::explicit::fixed_step_integrators;
use hooke::prelude::*;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// Whether this thread does the work measured: the test's thread and
    /// rayon's workers. The test harness's own thread allocates when it
    /// first waits for the test, which under load can fall inside a
    /// measurement; it is not the work.
    static WORKING: Cell<bool> = const { Cell::new(false) };
}

/// Counts one allocation if the calling thread does the work measured.
fn count() {
    if WORKING.with(Cell::get) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

/// Marks the calling thread as one that does the work measured.
fn working() {
    WORKING.with(|w| w.set(true));
}

// SAFETY: defers to the system allocator and only counts the calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { SystemAllocator.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { SystemAllocator.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { SystemAllocator.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `work`, on its own thread and rayon's workers.
fn allocations_during(work: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    work();
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

/// The counter is global, so this binary has a single test: the harness
/// allocates while it reports on other tests, and there are none.
///
/// With the `parallel` feature the test thread first joins rayon's global
/// pool as its worker 0 (`use_current_thread`), the way a program that
/// wants allocation-free parallel steps sets up its pool: a parallel call
/// from a worker queues its jobs in that worker's own deque, whose buffer
/// (64 jobs) never grows at the fan-out of a force evaluation, where a call
/// from outside the pool goes through rayon's injector, which allocates a
/// new block every 63 calls — a count no warm-up can line up. Then it
/// waits until every other worker has started (they allocate as they set
/// up) and marks them, like the test's thread, as doing the work: their
/// allocations count, the harness's do not.
#[test]
fn steady_state_work_does_not_allocate() {
    working();
    #[cfg(feature = "parallel")]
    rayon::ThreadPoolBuilder::new()
        .use_current_thread()
        .build_global()
        .expect("nothing in this binary built the global pool before");
    // A job on every worker: it runs once all of them have started.
    #[cfg(feature = "parallel")]
    rayon::broadcast(|_| working());
    steady_state_steps_do_not_allocate();
    implicit_steps_do_not_allocate();
    #[cfg(feature = "parallel")]
    parallel_force_evaluation_does_not_allocate();
    #[cfg(feature = "parallel")]
    parallel_implicit_steps_do_not_allocate();
}

/// Assembly, PCG and Cholesky (faer's numeric factorization and solve run in
/// storage allocated with the symbolic analysis), converged and linearised
/// steps, and error-controlled substeps.
fn implicit_steps_do_not_allocate() {
    use hooke::implicit::{ErrorControl, Implicit, LinearSolver, PcgSettings};
    let system = Sheet {
        damping: 0.05,
        ..Sheet::new(12)
    }
    .system()
    .unwrap();
    let pcg = LinearSolver::Pcg(PcgSettings::default());
    let integrators = [
        Implicit::backward_euler(),
        Implicit::backward_euler().with_solver(pcg),
        Implicit::backward_euler().linearized(),
        Implicit::bdf2(),
        Implicit::bdf2().with_solver(pcg),
        Implicit::bdf2().with_error_control(ErrorControl::new(1e-3, 1e-6).unwrap()),
    ];
    for mut integrator in integrators {
        let mut state = system.initial_state();
        for _ in 0..3 {
            integrator.step(&system, &mut state, 1e-2).unwrap();
        }
        let allocations = allocations_during(|| {
            for _ in 0..10 {
                integrator.step(&system, &mut state, 1e-2).unwrap();
            }
        });
        assert_eq!(
            allocations,
            0,
            "{} allocated {allocations} times in 10 steps",
            integrator.name()
        );
    }
}

/// Above `PARALLEL_MIN_PARTICLES` assembly, products and vector operations
/// run on rayon, still without allocating (PCG here: faer's parallel
/// sparse Cholesky allocates its task tree in every factorization). The
/// step runs on a worker of a rayon pool, as it does inside any parallel
/// application: a parallel call from outside the pool pushes its job onto
/// the pool's injector queue, which allocates a block per 63 jobs.
#[cfg(feature = "parallel")]
fn parallel_implicit_steps_do_not_allocate() {
    use hooke::implicit::internals::PARALLEL_MIN_PARTICLES;
    use hooke::implicit::{Implicit, LinearSolver, PcgSettings};
    let side = (PARALLEL_MIN_PARTICLES as f64).sqrt().ceil() as usize;
    let system = Sheet::new(side).system().unwrap();
    let mut integrator =
        Implicit::backward_euler().with_solver(LinearSolver::Pcg(PcgSettings::default()));
    let mut state = system.initial_state();
    let pool = rayon::ThreadPoolBuilder::new().build().unwrap();
    let allocations = pool.install(|| {
        integrator.step(&system, &mut state, 1e-4).unwrap();
        allocations_during(|| {
            integrator.step(&system, &mut state, 1e-4).unwrap();
        })
    });
    assert_eq!(
        allocations, 0,
        "a parallel implicit step allocated {allocations} times"
    );
}

fn steady_state_steps_do_not_allocate() {
    let system = HangingChain::new(20, 0.1, 500.0, 0.1)
        .damped(0.2, 0.01)
        .system()
        .unwrap();
    let mut integrators = fixed_step_integrators();
    integrators.push(Box::new(DormandPrince::default()));
    for mut integrator in integrators {
        let mut state = system.initial_state();
        for _ in 0..5 {
            integrator.step(&system, &mut state, 1e-3).unwrap();
        }
        let allocations = allocations_during(|| {
            for _ in 0..50 {
                integrator.step(&system, &mut state, 1e-3).unwrap();
            }
        });
        assert_eq!(
            allocations,
            0,
            "{} allocated {allocations} times in 50 steps",
            integrator.name()
        );
    }
}

#[cfg(feature = "parallel")]
fn parallel_force_evaluation_does_not_allocate() {
    use hooke::core::{ForceEvaluator, Parallelism};
    let system = Sheet::new(48).system().unwrap();
    let state = system.initial_state();
    let mut a = vec![Vec3::zeros(); system.particle_count()];
    let mut evaluator = ForceEvaluator::new(Parallelism::Parallel);
    for _ in 0..5 {
        evaluator.accelerations(&system, state.positions(), state.velocities(), &mut a);
    }
    let allocations = allocations_during(|| {
        for _ in 0..50 {
            evaluator.accelerations(&system, state.positions(), state.velocities(), &mut a);
        }
    });
    assert_eq!(
        allocations, 0,
        "parallel evaluation allocated {allocations} times in 50 calls"
    );
}
