//! PNG figures of a mechanism case, after \[Flores2009\] Figs. 13–15:
//!
//! - `CASE_forces.png` (Fig. 13): (a) the rod–slider joint's reaction force |F| and (b) the
//!   crank's driving moment against crank angle over all turns, lubricated (solid blue) and
//!   ideal (dashed black);
//! - `CASE_orbit.png` (Fig. 14): the journal-centre orbit e/c inside the clearance circle, the
//!   contact threshold (h_min = h_b) dashed red, the start marked, a dot every 90° of crank;
//! - every panel against crank angle shades where the dry contact acts (blend weight > 0);
//! - `CASE_film.png` (Fig. 15): the minimum film thickness h_min against crank angle with the
//!   paper's "safe" film ([`safe_film_thickness`], 3 µm for its joint) and the contact
//!   threshold h_b.
//!
//! The orbit and film figures need a lubricated run; an ideal case gets the forces figure only.
//! Style, font and tick helpers are those of [`crate::output::plots`].

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use jbearing_solvers::mechanism::{LubricatedJointParams, MechanismSolution};

use super::MechanismResults;
use crate::output::plots::{
    FAMILY, QUARTER, circle_points, crank_angle_chart, ensure_font, format_tick, format_unit_tick,
};
use crate::output::{OutputError, write_atomically};

/// The safe minimum film thickness drawn on the film figure, after \[Flores2009\] §8: at least
/// 0.00015 of the bearing diameter, and at least 2.5 µm (Hamrock's value, quoted there) —
/// "of order of 3 µm" for the paper's 20 mm joint.
pub fn safe_film_thickness(bearing_radius: f64) -> f64 {
    (1.5e-4 * 2.0 * bearing_radius).max(2.5e-6)
}

const LUBRICATED_COLOR: RGBColor = RGBColor(31, 87, 180);
const IDEAL_COLOR: RGBColor = RGBColor(20, 20, 20);
const SAFE_COLOR: RGBColor = RGBColor(230, 140, 0);
const CONTACT_COLOR: RGBColor = RGBColor(200, 20, 20);
const GREY: RGBColor = RGBColor(120, 120, 120);
const CONTACT_SHADE: RGBColor = RGBColor(255, 215, 215);

/// Figure sizes (pixels).
const FORCES_SIZE: (u32, u32) = (1400, 1100);
const ORBIT_SIZE: u32 = 950;
const FILM_SIZE: (u32, u32) = (1400, 650);

/// Paths of the figures for `r` in `dir` (the orbit and film figures only with a lubricated
/// run).
pub fn file_paths(r: &MechanismResults, dir: &Path) -> Vec<PathBuf> {
    let name = &r.case.name;
    let mut v = vec![dir.join(format!("{name}_forces.png"))];
    if r.lubricated.is_some() {
        v.push(dir.join(format!("{name}_orbit.png")));
        v.push(dir.join(format!("{name}_film.png")));
    }
    v
}

/// Draw the figures into `dir`; returns their paths.
pub fn write_plots(r: &MechanismResults, dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
    let paths = file_paths(r, dir);
    let plot_err = |path: &Path| {
        let path = path.to_path_buf();
        move |message: String| OutputError::Plot { path, message }
    };
    ensure_font().map_err(plot_err(&paths[0]))?;
    write_atomically(&paths[0], |tmp| {
        draw_forces(r, tmp).map_err(plot_err(&paths[0]))
    })?;
    if paths.len() == 3 {
        write_atomically(&paths[1], |tmp| {
            draw_orbit(r, tmp).map_err(plot_err(&paths[1]))
        })?;
        write_atomically(&paths[2], |tmp| {
            draw_film(r, tmp).map_err(plot_err(&paths[2]))
        })?;
    }
    Ok(paths)
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// The title (centred) on a strip of `height` pixels; returns the area below.
fn title<'a>(root: &Area<'a>, text: &str, height: u32) -> Result<Area<'a>, String> {
    let (top, body) = root.split_vertically(height);
    let (w, _) = top.dim_in_pixel();
    let font = (FAMILY, 28).into_font();
    let tw = top
        .estimate_text_size(text, &font.clone().into())
        .map_err(err)?
        .0;
    top.draw(&Text::new(
        text.to_string(),
        (((w as i32 - tw as i32) / 2).max(4), 12),
        font,
    ))
    .map_err(err)?;
    Ok(body)
}

/// A curve: label, colour, dashed, points (crank angle deg, value).
struct Curve {
    label: String,
    color: RGBColor,
    dashed: bool,
    points: Vec<(f64, f64)>,
}

/// A horizontal reference line: label, colour, value.
struct Level {
    label: String,
    color: RGBColor,
    value: f64,
}

/// Crank-angle intervals (deg) where the dry contact acts (blend weight > 0 at a sample).
pub fn contact_windows(crank: &[f64], weight: &[f64]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut start: Option<f64> = None;
    for (k, (&a, &w)) in crank.iter().zip(weight).enumerate() {
        match (w > 0.0, start) {
            (true, None) => start = Some(if k > 0 { crank[k - 1] } else { a }),
            (false, Some(s)) => {
                out.push((s, a));
                start = None;
            }
            _ => {}
        }
    }
    if let (Some(s), Some(&last)) = (start, crank.last()) {
        out.push((s, last));
    }
    out
}

/// One panel against crank angle: x over the whole run, ticks every 90°, TDC every 360°
/// dotted, the legend in a strip above the data; `shade` (crank-angle intervals) behind the
/// data, labelled "dry contact".
fn panel(
    area: &Area<'_>,
    heading: &str,
    ylabel: &str,
    curves: &[Curve],
    levels: &[Level],
    y_from_zero: bool,
    shade: &[(f64, f64)],
) -> Result<(), String> {
    let area = area.margin(4, 8, 8, 16);
    let (head, area) = area.split_vertically(64);
    head.draw(&Text::new(
        heading.to_string(),
        (96, 2),
        (FAMILY, 22).into_font(),
    ))
    .map_err(err)?;
    draw_legend_strip(&head, curves, levels, !shade.is_empty())?;
    let (x0, x1, y0, y1) = panel_ranges(curves, levels, y_from_zero);
    let mut chart = crank_angle_chart(&area, (x0, x1), (y0, y1), ylabel)?;
    for (a, b) in shade {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(a / QUARTER, y0), (b / QUARTER, y1)],
                CONTACT_SHADE.filled(),
            )))
            .map_err(err)?;
    }
    let mut tdc = (x0 / 360.0).ceil() * 360.0;
    while tdc <= x1 + 1e-9 {
        chart
            .draw_series(DashedLineSeries::new(
                [(tdc / QUARTER, y0), (tdc / QUARTER, y1)],
                3,
                5,
                GREY.stroke_width(2),
            ))
            .map_err(err)?;
        tdc += 360.0;
    }
    for l in levels {
        chart
            .draw_series(DashedLineSeries::new(
                [(x0 / QUARTER, l.value), (x1 / QUARTER, l.value)],
                10,
                6,
                l.color.stroke_width(2),
            ))
            .map_err(err)?;
    }
    for c in curves {
        let pts: Vec<(f64, f64)> = c.points.iter().map(|(x, y)| (x / QUARTER, *y)).collect();
        let style = c.color.stroke_width(if c.dashed { 2 } else { 3 });
        if c.dashed {
            chart
                .draw_series(DashedLineSeries::new(pts, 10, 6, style))
                .map_err(err)?;
        } else {
            // Segment by segment, as the orbit (no mitred spikes at impacts).
            chart
                .draw_series(
                    pts.windows(2)
                        .map(|w| PathElement::new(vec![w[0], w[1]], style)),
                )
                .map_err(err)?;
        }
    }
    Ok(())
}

/// The legend strip above a panel's data: one entry per curve and level, and the dry-contact
/// patch where the panel is `shaded`.
fn draw_legend_strip(
    head: &Area<'_>,
    curves: &[Curve],
    levels: &[Level],
    shaded: bool,
) -> Result<(), String> {
    let mut x = 96;
    let font = (FAMILY, 18).into_font();
    let entries = curves
        .iter()
        .map(|c| (c.label.as_str(), c.color, c.dashed))
        .chain(levels.iter().map(|l| (l.label.as_str(), l.color, true)))
        .map(|(l, c, d)| (l, c, d, false))
        .chain(shaded.then_some(("dry contact", CONTACT_SHADE, false, true)));
    for (label, color, dashed, patch) in entries {
        let y = 44;
        if patch {
            head.draw(&Rectangle::new(
                [(x, y - 9), (x + 36, y + 9)],
                color.filled(),
            ))
            .map_err(err)?;
        } else if dashed {
            for k in 0..3 {
                head.draw(&PathElement::new(
                    vec![(x + 14 * k, y), (x + 14 * k + 8, y)],
                    color.stroke_width(3),
                ))
                .map_err(err)?;
            }
        } else {
            head.draw(&PathElement::new(
                vec![(x, y), (x + 36, y)],
                color.stroke_width(3),
            ))
            .map_err(err)?;
        }
        head.draw(&Text::new(
            label.to_string(),
            (x + 44, y - 10),
            font.clone(),
        ))
        .map_err(err)?;
        let tw = head
            .estimate_text_size(label, &font.clone().into())
            .map_err(err)?
            .0 as i32;
        x += 44 + tw + 28;
    }
    Ok(())
}

/// The panel's crank-angle span and its value range over curves and levels, padded by 6 % (from
/// zero where `y_from_zero` and nothing is negative): `(x0, x1, y0, y1)`.
fn panel_ranges(curves: &[Curve], levels: &[Level], y_from_zero: bool) -> (f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (px, py) in curves.iter().flat_map(|c| c.points.iter()) {
        x0 = x0.min(*px);
        x1 = x1.max(*px);
        y0 = y0.min(*py);
        y1 = y1.max(*py);
    }
    for l in levels {
        y0 = y0.min(l.value);
        y1 = y1.max(l.value);
    }
    if y_from_zero {
        y0 = y0.min(0.0);
    }
    let pad = 0.06 * (y1 - y0).max(1e-12 * y1.abs().max(1.0));
    let (y0, y1) = (
        if y_from_zero && y0 >= 0.0 {
            0.0
        } else {
            y0 - pad
        },
        y1 + pad,
    );
    (x0, x1, y0, y1)
}

fn curves(r: &MechanismResults, value: impl Fn(&MechanismSolution, usize) -> f64) -> Vec<Curve> {
    let mut out = Vec::new();
    // The lubricated curve on top: drawn last.
    if let Some(s) = &r.ideal {
        out.push(Curve {
            label: "ideal joint".into(),
            color: IDEAL_COLOR,
            dashed: r.lubricated.is_some(),
            points: (0..s.time.len())
                .map(|i| (s.crank_angle_deg[i], value(s, i)))
                .collect(),
        });
    }
    if let Some(s) = &r.lubricated {
        out.push(Curve {
            label: format!("lubricated joint ({})", r.case.film_name),
            color: LUBRICATED_COLOR,
            dashed: false,
            points: (0..s.time.len())
                .map(|i| (s.crank_angle_deg[i], value(s, i)))
                .collect(),
        });
    }
    out
}

fn subtitle(r: &MechanismResults) -> String {
    match r.case.lubricated_joint() {
        Some(j) => format!(
            "{}: c = {:.3} mm, μ = {:.4} Pa s, {:.0} rpm",
            r.case.name,
            j.radial_clearance() * 1e3,
            j.viscosity,
            r.case.params.mechanism.crank_speed * 60.0 / std::f64::consts::TAU
        ),
        None => format!(
            "{}: ideal joints, {:.0} rpm",
            r.case.name,
            r.case.params.mechanism.crank_speed * 60.0 / std::f64::consts::TAU
        ),
    }
}

fn draw_forces(r: &MechanismResults, path: &Path) -> Result<(), String> {
    let root = BitMapBackend::new(path, FORCES_SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let body = title(&root, &subtitle(r), 56)?;
    let (a, b) = body.split_vertically(FORCES_SIZE.1.saturating_sub(56) / 2);
    let shade = r.lubricated.as_ref().map_or_else(Vec::new, |s| {
        contact_windows(&s.crank_angle_deg, &s.contact_weight)
    });
    let force = curves(r, |s, i| {
        let f = s.loads[i].rod_slider;
        f[0].hypot(f[1])
    });
    panel(
        &a,
        "(a) reaction force at the rod-slider joint |F|",
        "force [N]",
        &force,
        &[],
        true,
        &shade,
    )?;
    let moment = curves(r, |s, i| s.loads[i].crank_moment);
    panel(
        &b,
        "(b) crank driving moment M",
        "moment [N m]",
        &moment,
        &[],
        false,
        &shade,
    )?;
    root.present().map_err(err)
}

fn draw_film(r: &MechanismResults, path: &Path) -> Result<(), String> {
    let (Some(s), Some(j)) = (&r.lubricated, r.case.lubricated_joint()) else {
        return Err("no lubricated run".into());
    };
    let root = BitMapBackend::new(path, FILM_SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let body = title(&root, &subtitle(r), 56)?;
    let h = vec![Curve {
        label: format!("h_min, lubricated joint ({})", r.case.film_name),
        color: LUBRICATED_COLOR,
        dashed: false,
        points: s
            .crank_angle_deg
            .iter()
            .zip(&s.min_film_thickness)
            .map(|(a, h)| (*a, h * 1e6))
            .collect(),
    }];
    let levels = [
        Level {
            label: format!(
                "safe film {} µm",
                format_tick(safe_film_thickness(j.bearing_radius) * 1e6)
            ),
            color: SAFE_COLOR,
            value: safe_film_thickness(j.bearing_radius) * 1e6,
        },
        Level {
            label: format!(
                "contact threshold h_b = {} µm",
                format_tick(j.contact.boundary_layer * 1e6)
            ),
            color: CONTACT_COLOR,
            value: j.contact.boundary_layer * 1e6,
        },
    ];
    panel(
        &body,
        "minimum film thickness of the rod-slider joint",
        "h_min [µm]",
        &h,
        &levels,
        true,
        &contact_windows(&s.crank_angle_deg, &s.contact_weight),
    )?;
    root.present().map_err(err)
}

/// `CASE_orbit.png`: the journal orbit in the clearance circle, with the contact circle, a dot
/// every 90° of crank and the legend beside it.
fn draw_orbit(r: &MechanismResults, path: &Path) -> Result<(), String> {
    let (Some(s), Some(j)) = (&r.lubricated, r.case.lubricated_joint()) else {
        return Err("no lubricated run".into());
    };
    let c = j.radial_clearance();
    let legend_width = 380;
    let root =
        BitMapBackend::new(path, (ORBIT_SIZE + legend_width, ORBIT_SIZE + 56)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let body = title(
        &root,
        &format!("{}: journal orbit in the clearance circle", r.case.name),
        56,
    )?;
    let (plot, legend_area) = body.split_horizontally(ORBIT_SIZE);
    let mut chart = ChartBuilder::on(&plot)
        .margin(16)
        .x_label_area_size(64)
        .y_label_area_size(64)
        .build_cartesian_2d(-1.15f64..1.15f64, -1.15f64..1.15f64)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_labels(11)
        .y_labels(11)
        .x_desc("e_x / c")
        .y_desc("e_y / c")
        .label_style((FAMILY, 17).into_font())
        .axis_desc_style((FAMILY, 20).into_font())
        .x_label_formatter(&|v| format_unit_tick(*v))
        .y_label_formatter(&|v| format_unit_tick(*v))
        .light_line_style(TRANSPARENT)
        .draw()
        .map_err(err)?;
    chart
        .draw_series(LineSeries::new(circle_points(1.0), BLACK.stroke_width(2)))
        .map_err(err)?;
    for radius in [0.25, 0.5, 0.75] {
        chart
            .draw_series(DashedLineSeries::new(
                circle_points(radius),
                4,
                6,
                RGBColor(170, 170, 170).stroke_width(1),
            ))
            .map_err(err)?;
    }
    let contact = 1.0 - j.contact.boundary_layer / c;
    chart
        .draw_series(DashedLineSeries::new(
            circle_points(contact),
            10,
            6,
            CONTACT_COLOR.stroke_width(2),
        ))
        .map_err(err)?;
    draw_journal_path(&mut chart, r, s, c)?;
    draw_orbit_legend(&legend_area, r, j)?;
    root.present().map_err(err)
}

/// The orbit plot's axes: e / c both ways.
type OrbitChart<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// The journal centre's path in e / c, a labelled dot every 90° of crank after the start and
/// the start itself.
fn draw_journal_path(
    chart: &mut OrbitChart<'_, '_>,
    r: &MechanismResults,
    s: &MechanismSolution,
    c: f64,
) -> Result<(), String> {
    let pts: Vec<(f64, f64)> = s
        .eccentricity
        .iter()
        .map(|e| (e[0] / c, e[1] / c))
        .collect();
    // Segment by segment: a thick polyline's mitred joins spike far out where the path turns
    // back on itself over a few µm (an impact), drawing lines the journal never went along.
    chart
        .draw_series(
            pts.windows(2)
                .map(|w| PathElement::new(vec![w[0], w[1]], LUBRICATED_COLOR.stroke_width(3))),
        )
        .map_err(err)?;
    // A dot every 90° of crank after the first turn's start, labelled.
    let turn = r.case.params.samples_per_turn;
    for (i, p) in pts.iter().enumerate().skip(1) {
        if (i * 4) % turn == 0 {
            chart
                .draw_series(std::iter::once(Circle::new(
                    *p,
                    5,
                    LUBRICATED_COLOR.filled(),
                )))
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{:.0}°", s.crank_angle_deg[i]),
                    (p.0 + 0.02, p.1 + 0.02),
                    (FAMILY, 15).into_font(),
                )))
                .map_err(err)?;
        }
    }
    chart
        .draw_series(std::iter::once(Circle::new(pts[0], 8, BLACK.filled())))
        .map_err(err)?;
    Ok(())
}

/// The orbit plot's legend beside the circle: clearance, contact circle, journal centre, start.
fn draw_orbit_legend(
    legend_area: &Area<'_>,
    r: &MechanismResults,
    j: &LubricatedJointParams,
) -> Result<(), String> {
    let c = j.radial_clearance();
    let font = (FAMILY, 19).into_font();
    let rows: [(String, RGBColor, bool); 4] = [
        (
            format!("clearance circle, c = {:.1} µm", c * 1e6),
            BLACK,
            false,
        ),
        (
            format!(
                "contact: h_min = h_b = {} µm",
                format_tick(j.contact.boundary_layer * 1e6)
            ),
            CONTACT_COLOR,
            true,
        ),
        (
            format!("journal centre ({})", r.case.film_name),
            LUBRICATED_COLOR,
            false,
        ),
        ("start (centred); dots every 90°".to_string(), BLACK, false),
    ];
    for (k, (label, color, dashed)) in rows.iter().enumerate() {
        let y = 80 + 40 * k as i32;
        if k == 3 {
            legend_area
                .draw(&Circle::new((28, y), 8, BLACK.filled()))
                .map_err(err)?;
        } else if *dashed {
            for q in 0..3 {
                legend_area
                    .draw(&PathElement::new(
                        vec![(10 + 14 * q, y), (18 + 14 * q, y)],
                        color.stroke_width(3),
                    ))
                    .map_err(err)?;
            }
        } else {
            legend_area
                .draw(&PathElement::new(
                    vec![(10, y), (46, y)],
                    color.stroke_width(3),
                ))
                .map_err(err)?;
        }
        legend_area
            .draw(&Text::new(label.clone(), (54, y - 10), font.clone()))
            .map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::contact_windows;

    #[test]
    fn contact_windows_span_the_samples_in_contact() {
        let crank = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        assert_eq!(contact_windows(&crank, &[0.0; 6]), vec![]);
        assert_eq!(
            contact_windows(&crank, &[0.0, 0.0, 0.5, 1.0, 0.0, 0.2]),
            vec![(1.0, 4.0), (4.0, 5.0)]
        );
        assert_eq!(
            contact_windows(&crank, &[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
            vec![(0.0, 1.0)]
        );
    }
}
