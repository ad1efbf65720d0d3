//! The figure of the README's deformable-bearing section: [Benasciutti2012] JB1 (α = 0,
//! T 40 → 80 °C linear) rigid and with elastic shaft and housing (steel, hole 0.4 R, square
//! housing of half-width 2R), the film pressure (the paper's Fig. 6a), the meatus (Fig. 6b)
//! and the stresses along the housing bore (Fig. 7c), against the angle from the load line.
//!
//! `cargo run --release --example elastic_jb1 -- docs/benasciutti_jb1_elastic.png`

use std::f64::consts::PI;

use jbearing_solvers::elastic::{ElasticBearing, ElasticParams, solve_steady_load};
use jbearing_solvers::reynolds::{
    FilmSolution, GridParams, OperatingConditions, ReynoldsParams, ReynoldsSolver, SupplyModel,
};
use jbearing_solvers::viscosity::{Temperature, ViscosityModel, Vogel};
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
    let conditions = OperatingConditions {
        journal_speed: 65.0 * 2.0 * PI / 60.0,
        bearing_speed: 0.0,
        feed_pressures: vec![],
    };
    let mut solver = film();
    let load = [0.0, -3.6e6 / 0.3 * solver.params().length];
    let (rigid, rigid_info) = solver.solve_steady_load(load, &conditions)?;
    let bearing = ElasticBearing::new(R, ElasticParams::steel(R))?;
    let (sol, info) = solve_steady_load(&mut solver, &bearing, load, &conditions)?;
    let angles = bearing.surface_angles();
    let [erx, ery] = rigid_info.eccentricity_ratio;
    let [edx, edy] = info.steady.eccentricity_ratio;
    let h_rigid = sorted(
        angles
            .iter()
            .map(|&t| {
                (
                    from_load(t),
                    C * (1.0 - erx * t.cos() - ery * t.sin()) * 1e3,
                )
            })
            .collect(),
    );
    let h_def = sorted(
        angles
            .iter()
            .zip(&sol.gap_change)
            .map(|(&t, g)| {
                (
                    from_load(t),
                    (C * (1.0 - edx * t.cos() - edy * t.sin()) + g) * 1e3,
                )
            })
            .collect(),
    );
    let stresses = bearing.housing.stresses(&sol.housing_displacement);
    let mesh = bearing.housing.mesh();
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
    let comps = comps.map(sorted);

    let root = BitMapBackend::new(&out, (900, 1200)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((3, 1));
    let font = ("sans-serif", 16);
    // (a) pressure.
    let mut ch = ChartBuilder::on(&panels[0])
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
        pressure_curve(&rigid),
        BLUE.stroke_width(2),
    ))?
    .label(format!("rigid, p_max {:.1} MPa", rigid.max_pressure / 1e6))
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    ch.draw_series(LineSeries::new(
        pressure_curve(&sol.film),
        RED.stroke_width(2),
    ))?
    .label(format!(
        "elastic, p_max {:.1} MPa (paper 83 -> 43 MPa)",
        sol.film.max_pressure / 1e6
    ))
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    ch.configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .border_style(BLACK)
        .background_style(WHITE)
        .label_font(font)
        .draw()?;
    // (b) meatus.
    let mut ch = ChartBuilder::on(&panels[1])
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
    ch.draw_series(LineSeries::new(h_rigid, BLUE.stroke_width(2)))?
        .label(format!("rigid, e {:.4} mm", C * erx.hypot(ery) * 1e3))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    ch.draw_series(LineSeries::new(h_def, RED.stroke_width(2)))?
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
    // (c) bore stresses.
    let mut ch = ChartBuilder::on(&panels[2])
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
    for ((c, color), name) in comps.into_iter().zip(colors).zip(names) {
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
    root.present()?;
    println!("wrote {out}");
    Ok(())
}
