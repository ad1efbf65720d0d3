//! The figure of the README's deformable-bearing section: [Benasciutti2012] JB1 (α = 0,
//! T 40 → 80 °C linear) rigid and with elastic shaft and housing (steel, hole 0.4 R, square
//! housing of half-width 2R), the film pressure (the paper's Fig. 6a), the meatus (Fig. 6b)
//! and the stresses along the housing bore (Fig. 7c), against the angle from the load line.
//!
//! `cargo run --release --example elastic_jb1 -- docs/benasciutti_jb1_elastic.png`

use std::f64::consts::PI;

use jbearing_solvers::elastic::{
    ElasticBearing, ElasticParams, ElasticSolution, solve_steady_load,
};
use jbearing_solvers::reynolds::{
    FilmSolution, GridParams, OperatingConditions, ReynoldsParams, ReynoldsSolver, SupplyModel,
};
use jbearing_solvers::viscosity::{Temperature, ViscosityModel, Vogel};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;

const R: f64 = 0.25;
const C: f64 = 0.25e-3;
const FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

fn film() -> ReynoldsSolver {
    let l = 100.0 * 2.0 * R;
    let mut p = ReynoldsParams::plain(R, l, C, 0.1678);
    p.supply = SupplyModel::AxialLineAtMaxGap;
    p.viscosity_model = Some(ViscosityModel {
        vogel: Vogel::seed003_iso_vg_680(),
        temperature: Temperature::LinearOverSpan {
            inlet: 40.0,
            outlet: 80.0,
            span: PI,
        },
        pressure_coefficient: 0.0,
    });
    p.grid = GridParams {
        n_theta: 240,
        n_z: 5,
    };
    p.bulk_modulus = 1.5e13;
    ReynoldsSolver::new(p).unwrap()
}

/// Angle from the load line (−y) in the direction of rotation, deg in (−180, 180].
fn from_load(theta: f64) -> f64 {
    let x = (theta + PI / 2.0).to_degrees().rem_euclid(360.0);
    if x > 180.0 { x - 360.0 } else { x }
}

/// (angle from the load line, mid-row pressure MPa), sorted by angle.
fn pressure_curve(f: &FilmSolution) -> Vec<(f64, f64)> {
    let nz = f.z.len();
    let mut v: Vec<(f64, f64)> = f
        .theta
        .iter()
        .enumerate()
        .map(|(i, &th)| (from_load(th), f.pressure[[i, nz / 2]] / 1e6))
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

fn sorted(mut v: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "docs/benasciutti_jb1_elastic.png".into());
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| "font registration failed")?;
    let jb1 = solve_jb1()?;
    let root = BitMapBackend::new(&out, (900, 1200)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((3, 1));
    draw_pressure(&panels[0], &jb1)?;
    draw_meatus(&panels[1], &jb1)?;
    draw_stresses(&panels[2], &jb1)?;
    root.present()?;
    println!("wrote {out}");
    Ok(())
}

/// JB1 under the paper's load at 65 rpm, rigid and with elastic shaft and housing.
struct Jb1 {
    rigid: FilmSolution,
    rigid_eccentricity: [f64; 2],
    elastic: ElasticSolution,
    elastic_eccentricity: [f64; 2],
    bearing: ElasticBearing,
}

/// The two steady solves: the rigid film, then the film coupled with the deformation.
fn solve_jb1() -> Result<Jb1, Box<dyn std::error::Error>> {
    let conditions = OperatingConditions {
        journal_speed: 65.0 * 2.0 * PI / 60.0,
        bearing_speed: 0.0,
        feed_pressures: vec![],
    };
    let mut solver = film();
    let load = [0.0, -3.6e6 / 0.3 * solver.params().length];
    let (rigid, rigid_info) = solver.solve_steady_load(load, &conditions)?;
    let bearing = ElasticBearing::new(R, ElasticParams::steel(R))?;
    let (elastic, info) = solve_steady_load(&mut solver, &bearing, load, &conditions)?;
    Ok(Jb1 {
        rigid,
        rigid_eccentricity: rigid_info.eccentricity_ratio,
        elastic,
        elastic_eccentricity: info.steady.eccentricity_ratio,
        bearing,
    })
}

/// (angle from the load line, meatus mm) at the surface nodes, sorted by angle: h = c (1 − ε_x
/// cos θ − ε_y sin θ) of the rigid bearing, or of the elastic one plus its gap change.
fn meatus(jb1: &Jb1, elastic: bool) -> Vec<(f64, f64)> {
    let angles = jb1.bearing.surface_angles();
    let h = |t: f64, [ex, ey]: [f64; 2]| C * (1.0 - ex * t.cos() - ey * t.sin());
    let curve = if elastic {
        angles
            .iter()
            .zip(&jb1.elastic.gap_change)
            .map(|(&t, g)| (from_load(t), (h(t, jb1.elastic_eccentricity) + g) * 1e3))
            .collect()
    } else {
        angles
            .iter()
            .map(|&t| (from_load(t), h(t, jb1.rigid_eccentricity) * 1e3))
            .collect()
    };
    sorted(curve)
}

/// σ_r, σ_θ, σ_z and von Mises (MPa) along the housing bore against the angle from the load
/// line, each sorted by angle.
fn bore_stresses(jb1: &Jb1) -> [Vec<(f64, f64)>; 4] {
    let housing = &jb1.bearing.housing;
    let stresses = housing.stresses(&jb1.elastic.housing_displacement);
    let mesh = housing.mesh();
    let mut comps: [Vec<(f64, f64)>; 4] = Default::default();
    for &node in &mesh.surface {
        let [x, y] = mesh.nodes[node];
        let t = y.atan2(x);
        let [sr, st, _] = stresses[node].polar(t);
        let a = from_load(t);
        for (c, v) in comps
            .iter_mut()
            .zip([sr, st, stresses[node].zz, stresses[node].von_mises()])
        {
            c.push((a, v / 1e6));
        }
    }
    comps.map(sorted)
}

type Panel<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// (a) The mid-plane film pressure, rigid and elastic (the paper's Fig. 6a).
fn draw_pressure(panel: &Panel<'_>, jb1: &Jb1) -> Result<(), Box<dyn std::error::Error>> {
    let font = ("sans-serif", 16);
    let mut ch = ChartBuilder::on(panel)
        .caption(
            "JB1 film pressure (mid-plane): rigid vs elastic shaft and housing",
            font,
        )
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(56)
        .build_cartesian_2d(-180.0..180.0, 0.0..100.0)?;
    ch.configure_mesh()
        .x_desc("angle from the load line, direction of rotation [deg]")
        .y_desc("p [MPa]")
        .label_style(font)
        .draw()?;
    ch.draw_series(LineSeries::new(
        pressure_curve(&jb1.rigid),
        BLUE.stroke_width(2),
    ))?
    .label(format!(
        "rigid, p_max {:.1} MPa",
        jb1.rigid.max_pressure / 1e6
    ))
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    ch.draw_series(LineSeries::new(
        pressure_curve(&jb1.elastic.film),
        RED.stroke_width(2),
    ))?
    .label(format!(
        "elastic, p_max {:.1} MPa (paper 83 -> 43 MPa)",
        jb1.elastic.film.max_pressure / 1e6
    ))
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    ch.configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .border_style(BLACK)
        .background_style(WHITE)
        .label_font(font)
        .draw()?;
    Ok(())
}

/// (b) The meatus h(θ), rigid and elastic (the paper's Fig. 6b).
fn draw_meatus(panel: &Panel<'_>, jb1: &Jb1) -> Result<(), Box<dyn std::error::Error>> {
    let font = ("sans-serif", 16);
    let [erx, ery] = jb1.rigid_eccentricity;
    let [edx, edy] = jb1.elastic_eccentricity;
    let mut ch = ChartBuilder::on(panel)
        .caption("meatus h(θ)", font)
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(56)
        .build_cartesian_2d(-180.0..180.0, 0.0..0.6)?;
    ch.configure_mesh()
        .x_desc("angle from the load line [deg]")
        .y_desc("h [mm]")
        .label_style(font)
        .draw()?;
    ch.draw_series(LineSeries::new(meatus(jb1, false), BLUE.stroke_width(2)))?
        .label(format!("rigid, e {:.4} mm", C * erx.hypot(ery) * 1e3))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    ch.draw_series(LineSeries::new(meatus(jb1, true), RED.stroke_width(2)))?
        .label(format!(
            "elastic, e {:.4} mm (paper 0.2392 -> 0.2953 mm)",
            C * edx.hypot(edy) * 1e3
        ))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    ch.configure_series_labels()
        .position(SeriesLabelPosition::UpperMiddle)
        .border_style(BLACK)
        .background_style(WHITE)
        .label_font(font)
        .draw()?;
    Ok(())
}

/// (c) The stresses along the housing bore, plane strain (the paper's Fig. 7c).
fn draw_stresses(panel: &Panel<'_>, jb1: &Jb1) -> Result<(), Box<dyn std::error::Error>> {
    let font = ("sans-serif", 16);
    let mut ch = ChartBuilder::on(panel)
        .caption("housing bore stresses (plane strain)", font)
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(56)
        .build_cartesian_2d(-180.0..180.0, -55.0..45.0)?;
    ch.configure_mesh()
        .x_desc("angle from the load line [deg]")
        .y_desc("stress [MPa]")
        .label_style(font)
        .draw()?;
    let colors = [RED, BLUE, GREEN, BLACK];
    let names = [
        "σ_r",
        "σ_θ",
        "σ_z = ν(σ_r + σ_θ)",
        "von Mises (paper max 21 MPa)",
    ];
    for ((c, color), name) in bore_stresses(jb1).into_iter().zip(colors).zip(names) {
        ch.draw_series(LineSeries::new(c, color.stroke_width(2)))?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    ch.configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .border_style(BLACK)
        .background_style(WHITE)
        .label_font(font)
        .draw()?;
    Ok(())
}
