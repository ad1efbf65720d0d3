//! Timing report of the slider-crank with a lubricated joint (issue 16, item 5): \[Flores2009\]'s
//! example (Table 2 mechanism at 5000 rpm, Table 3 joint, c = 0.2 mm, μ = 400 cP), two crank
//! turns from the start, as `solve_mechanism` runs it by default:
//!
//! - every closed-form film with the adaptive Radau5 integrator (target ≤ 50 ms per run);
//! - the same with fixed-step BDF2 at 360 steps per turn, and with BDF2 under error control
//!   (`Integrator::bdf2_controlled`, the Reynolds film's default);
//! - the mass-conserving Reynolds film at its default grid (120 × 31) with its default
//!   integrator, BDF2 under error control (target ≤ 10 s per run).
//!
//! Times are CPU time of this thread (`CLOCK_THREAD_CPUTIME_ID`), so other processes on a shared
//! machine inflate them little; release build, one core; each row is the median of N runs.
//!
//! Usage: `cargo run --release -p jbearing-validation --bin mechanism_timing [-- [--quick]
//! [--repeat N] [--write-docs]]` (`--quick`: the closed forms only; `--repeat N`: runs per row,
//! default 21 for the closed forms and 3 for the Reynolds film; `--write-docs`: also put the
//! report into docs/performance.md in place of the block `<!-- BEGIN generated: COMMAND -->` …
//! `<!-- END generated -->`, COMMAND being this command line without `--write-docs`).

use anyhow::{Context, Result};
use jbearing_solvers::closed_form::ClosedFormModel;
use jbearing_solvers::mechanism::{
    DEFAULT_BDF2_ERROR_TOLERANCE, Integrator, JointFilm, LubricatedJointParams, MechanismParams,
    MechanismSolution, RodSliderJoint, SliderCrankParams, solve_mechanism,
};
use jbearing_validation::generated_docs::{docs_page, machine, take_report, write_generated_block};
use jbearing_validation::report;

fn thread_cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid, writable timespec; CLOCK_THREAD_CPUTIME_ID is supported by every
    // Linux kernel since 2.6.12.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID) failed");
    t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
}

/// Median time (s) of `repeat` runs and the last solution.
fn time_runs(params: &MechanismParams, repeat: usize) -> Result<(f64, MechanismSolution)> {
    let mut times = Vec::with_capacity(repeat);
    let mut last = None;
    for _ in 0..repeat {
        let t0 = thread_cpu_seconds();
        let s = solve_mechanism(params).context("mechanism run")?;
        times.push(thread_cpu_seconds() - t0);
        last = Some(s);
    }
    times.sort_by(f64::total_cmp);
    Ok((times[times.len() / 2], last.expect("repeat ≥ 1")))
}

fn row(label: &str, integrator: &str, seconds: f64, s: &MechanismSolution) {
    let i = &s.info;
    report!(
        "| {label} | {integrator} | {:.2} | {} | {} | {} | {:.1} | {:.0} | {:.2} |",
        1e3 * seconds,
        i.steps,
        i.evaluations,
        i.film_steps,
        1e6 * i.min_film_thickness.unwrap_or(f64::NAN),
        i.max_joint_force,
        i.max_crank_moment,
    );
}

fn main() -> Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let write_docs = args.iter().any(|a| a == "--write-docs");
    args.retain(|a| a != "--write-docs");
    let quick = args.iter().any(|a| a == "--quick");
    let repeat: Option<usize> = match args.iter().position(|a| a == "--repeat") {
        Some(i) => Some(
            args.get(i + 1)
                .and_then(|v| v.parse().ok())
                .filter(|&n: &usize| n >= 1)
                .context("--repeat needs a positive count")?,
        ),
        None => None,
    };
    for a in &args {
        if !(a == "--quick" || a == "--repeat" || a.parse::<usize>().is_ok()) {
            anyhow::bail!("unknown argument {a:?} (expected --quick, --repeat N, --write-docs)");
        }
    }
    report!(
        "Machine: {}. Measured: {}. Thread CPU time, one core, release build. [Flores2009] §8: \
         5000 rpm, c = 0.2 mm, μ = 400 cP, two crank turns from the start, 360 samples per turn.\n",
        machine(),
        jiff::Timestamp::now().strftime("%Y-%m-%d %H:%M UTC"),
    );
    report!(
        "| film | integrator | median time (ms) | steps | evaluations / Newton iterations | film steps | min h_min (µm) | max joint force (N) | max crank moment (N m) |"
    );
    report!("|---|---|---|---|---|---|---|---|---|");
    let mech = SliderCrankParams::flores2009();
    let cf_repeat = repeat.unwrap_or(21);
    for model in ClosedFormModel::ALL {
        let mut joint = LubricatedJointParams::flores2009();
        joint.film = JointFilm::ClosedForm(model);
        let mut p = MechanismParams::new(mech, RodSliderJoint::Lubricated(joint));
        let (t, s) = time_runs(&p, cf_repeat)?;
        row(model.name(), "Radau5", t, &s);
        p.integrator = Integrator::bdf2_fixed();
        let (t, s) = time_runs(&p, cf_repeat)?;
        row(model.name(), "BDF2 360/turn", t, &s);
        p.integrator = Integrator::bdf2_controlled();
        let (t, s) = time_runs(&p, cf_repeat)?;
        let controlled = format!("BDF2 error control {DEFAULT_BDF2_ERROR_TOLERANCE:e}");
        row(model.name(), &controlled, t, &s);
    }
    if !quick {
        let mut joint = LubricatedJointParams::flores2009();
        joint.film = JointFilm::Reynolds(Box::new(joint.reynolds_params()));
        let p = MechanismParams::new(mech, RodSliderJoint::Lubricated(joint));
        assert_eq!(
            p.integrator,
            Integrator::bdf2_controlled(),
            "the default is timed"
        );
        let (t, s) = time_runs(&p, repeat.unwrap_or(3))?;
        let controlled = format!(
            "BDF2 error control {DEFAULT_BDF2_ERROR_TOLERANCE:e} (default; {} rejected)",
            s.info.rejected_steps
        );
        row("Reynolds 120 × 31", &controlled, t, &s);
        report!(
            "\nReynolds film: {:.2} film steps per time step, {:.2} ms per film step (with the exact \
             Jacobian's solves).",
            s.info.film_steps as f64 / s.info.steps as f64,
            1e3 * t / s.info.film_steps as f64
        );
    }
    if write_docs {
        // The block is named by the command that measured it, --write-docs left out.
        let mut command =
            "cargo run --release -p jbearing-validation --bin mechanism_timing".to_string();
        if !args.is_empty() {
            command = format!("{command} -- {}", args.join(" "));
        }
        let page = docs_page("performance.md");
        write_generated_block(&page, &command, &take_report())?;
        eprintln!("wrote the block of {command:?} in {}", page.display());
    }
    Ok(())
}
