//! PNG plots of one case, after Yu & Sawicki (2002), Figs. 3 and 4.
//!
//! `CASE_cycle.png` — six panels against crank angle, rigorous (solid blue) and mobility (dashed
//! red) overlaid where both methods have the quantity:
//!
//! ```text
//!   (a) load components W_x, W_y [kN]      (b) feed pressure [MPa]
//!   (c) eccentricity ratio [–]             (d) minimum film thickness [µm]
//!   (e) flow rate: supply, side leakage    (f) power loss [W]
//!       [cm³/s]
//! ```
//!
//! `CASE_orbit.png` — the journal-centre orbit e/c in the clearance circle (|e| = c), bearing
//! frame, both methods, with the position at the first sample marked.
//!
//! Series are looked up by the standard names of [`super::names`]; a panel whose series no method
//! has says "not computed" instead of drawing nothing silently. Loads and feed pressure are inputs
//! shared by both methods and are drawn from the first method that has them.
//!
//! Text is rendered with plotters' `ab_glyph` backend from DejaVu Sans embedded in the binary
//! (`assets/fonts/`, Bitstream Vera licence), so plotting needs no system fonts, fontconfig or
//! freetype, and the pictures are the same on every machine.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;

use super::{CaseReport, Method, MethodResult, OutputError, OutputWriter, names, write_atomically};

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
const FAMILY: &str = "sans-serif";

fn ensure_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FAMILY, FontStyle::Normal, FONT)
                .map_err(|_| "the embedded DejaVu Sans font could not be parsed".to_string())
        })
        .clone()
}

/// Writes `CASE_cycle.png` and `CASE_orbit.png`.
#[derive(Debug, Clone, Copy)]
pub struct PlotWriter {
    /// Size of the six-panel figure in pixels.
    pub cycle_size: (u32, u32),
    /// Size of the (square) orbit figure in pixels.
    pub orbit_size: u32,
}

impl Default for PlotWriter {
    fn default() -> Self {
        Self {
            cycle_size: (1500, 1500),
            orbit_size: 900,
        }
    }
}

impl PlotWriter {
    /// Paths of the cycle and orbit figures for `report` in `dir`.
    pub fn file_paths(report: &CaseReport, dir: &Path) -> [PathBuf; 2] {
        [
            dir.join(format!("{}_cycle.png", report.case_name)),
            dir.join(format!("{}_orbit.png", report.case_name)),
        ]
    }
}

impl OutputWriter for PlotWriter {
    fn name(&self) -> &'static str {
        "plots"
    }

    fn write(&self, report: &CaseReport, dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
        report.validate()?;
        let [cycle, orbit] = Self::file_paths(report, dir);
        let plot_err = |path: &Path| {
            let path = path.to_path_buf();
            move |message: String| OutputError::Plot { path, message }
        };
        ensure_font().map_err(plot_err(&cycle))?;
        write_atomically(&cycle, |tmp| {
            draw_cycle(report, tmp, self.cycle_size).map_err(plot_err(&cycle))
        })?;
        write_atomically(&orbit, |tmp| {
            draw_orbit(report, tmp, self.orbit_size).map_err(plot_err(&orbit))
        })?;
        Ok(vec![cycle, orbit])
    }
}

/// Style of a method's curves.
fn method_color(m: Method) -> RGBColor {
    match m {
        Method::Rigorous => RGBColor(31, 87, 180),
        Method::Mobility => RGBColor(205, 45, 40),
    }
}

/// A panel of the cycle figure: title, y label, the (series name, legend label) pairs, and
/// whether the series are inputs shared by the methods (drawn once).
type PanelSpec = (
    &'static str,
    &'static str,
    Vec<(&'static str, &'static str)>,
    bool,
);

/// One curve of a panel.
struct Curve {
    label: String,
    color: RGBColor,
    dashed: bool,
    points: Vec<(f64, f64)>,
}

/// Display scaling of SI units.
fn display_scale(units: &str) -> (f64, &'static str) {
    match units {
        "N" => (1e-3, "kN"),
        "Pa" => (1e-6, "MPa"),
        "m" => (1e6, "µm"),
        "m3 s-1" | "m3/s" | "m^3/s" => (1e6, "cm³/s"),
        "W" => (1.0, "W"),
        "1" | "" => (1.0, "–"),
        _ => (1.0, "?"),
    }
}

fn curve_of(
    m: &MethodResult,
    name: &str,
    label: String,
    color: RGBColor,
    dashed: bool,
) -> Option<(Curve, String)> {
    let s = m.series(name)?;
    let (f, unit) = display_scale(&s.units);
    let unit = if unit == "?" {
        s.units.clone()
    } else {
        unit.to_string()
    };
    let points = m
        .crank_angle
        .iter()
        .zip(&s.values)
        .map(|(c, v)| (*c, v * f))
        .collect();
    Some((
        Curve {
            label,
            color,
            dashed,
            points,
        },
        unit,
    ))
}

/// Panel content: the curves of `series` for every method, or for the first method that has
/// them when `shared` (inputs such as the load).
fn method_curves(
    r: &CaseReport,
    series: &[(&str, &str)],
    shared: bool,
) -> (Vec<Curve>, Option<String>) {
    let mut curves = Vec::new();
    let mut unit = None;
    for (k, (name, label)) in series.iter().enumerate() {
        for m in &r.methods {
            let dashed = if shared {
                k % 2 == 1
            } else {
                m.method == Method::Mobility
            };
            let color = if shared {
                [RGBColor(31, 87, 180), RGBColor(20, 140, 70)][k % 2]
            } else {
                let c = method_color(m.method);
                // Second series of a panel (side leakage) in a lighter shade of the method.
                if k == 0 {
                    c
                } else {
                    RGBColor(c.0 / 2 + 110, c.1 / 2 + 110, c.2 / 2 + 110)
                }
            };
            let label = if shared {
                (*label).to_string()
            } else if series.len() > 1 {
                format!("{label}, {}", m.method)
            } else {
                m.method.to_string()
            };
            if let Some((c, u)) = curve_of(m, name, label, color, dashed) {
                unit.get_or_insert(u);
                curves.push(c);
                if shared {
                    break;
                }
            }
        }
    }
    (curves, unit)
}

fn draw_cycle(r: &CaseReport, path: &Path, size: (u32, u32)) -> Result<(), String> {
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let styles: Vec<String> = r
        .methods
        .iter()
        .map(|m| match m.method {
            Method::Rigorous => "rigorous (solid)".to_string(),
            Method::Mobility => "mobility (dashed)".to_string(),
        })
        .collect();
    let title = format!(
        "{}: {} against crank angle",
        r.case_name,
        styles.join(" and ")
    );
    let body = root
        .titled(&title, (FAMILY, 30).into_font())
        .map_err(|e| e.to_string())?;
    let panels = body.split_evenly((3, 2));
    let specs: [PanelSpec; 6] = [
        (
            "(a) Load components",
            "load",
            vec![(names::LOAD_X, "W_x"), (names::LOAD_Y, "W_y")],
            true,
        ),
        (
            "(b) Feed pressure",
            "p_feed",
            vec![(names::FEED_PRESSURE, "feed pressure")],
            true,
        ),
        (
            "(c) Eccentricity ratio",
            "ε",
            vec![(names::ECCENTRICITY_RATIO, "")],
            false,
        ),
        (
            "(d) Minimum film thickness",
            "h_min",
            vec![(names::MIN_FILM_THICKNESS, "")],
            false,
        ),
        (
            "(e) Flow rate",
            "flow",
            vec![
                (names::SUPPLY_FLOW, "supply"),
                (names::SIDE_LEAKAGE, "side leakage"),
            ],
            false,
        ),
        (
            "(f) Power loss",
            "power loss",
            vec![(names::POWER_LOSS, "")],
            false,
        ),
    ];
    for (area, (title, ylabel, series, shared)) in panels.iter().zip(specs) {
        let (curves, unit) = method_curves(r, &series, shared);
        let ylabel = format!("{ylabel} [{}]", unit.unwrap_or_default());
        draw_panel(area, title, &ylabel, &curves)?;
    }
    root.present().map_err(|e| e.to_string())
}

fn padded_range(lo: f64, hi: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if span <= 1e-12 * lo.abs().max(hi.abs()).max(1e-300) {
        // A constant: centre it in a band of ±10 % (or ±1 around zero).
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return (lo - d, hi + d);
    }
    (lo - 0.06 * span, hi + 0.06 * span)
}

fn draw_panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    title: &str,
    ylabel: &str,
    curves: &[Curve],
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let area = area.margin(8, 8, 8, 16);
    if curves.is_empty() {
        area.draw(&Text::new(
            format!("{title}: not computed"),
            (40, 60),
            (FAMILY, 22).into_font(),
        ))
        .map_err(e)?;
        return Ok(());
    }
    let all = curves.iter().flat_map(|c| c.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in all {
        x0 = x0.min(*x);
        x1 = x1.max(*x);
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    let (y0, y1) = padded_range(y0, y1);
    // A single instant (steady case): centre it on a 90° window.
    let (x0, x1) = if x1 > x0 {
        (x0, x1)
    } else {
        (x0 - 45.0, x0 + 45.0)
    };
    // The x axis runs in quarter turns (crank angle / 90°) so that plotters' "nice" tick values
    // (integers) fall on 0°, 90°, 180°, … as in the paper's figures; labels show degrees.
    const QUARTER: f64 = 90.0;
    let mut chart = ChartBuilder::on(&area)
        .caption(title, (FAMILY, 24).into_font())
        .x_label_area_size(48)
        .y_label_area_size(86)
        .build_cartesian_2d(x0 / QUARTER..x1 / QUARTER, y0..y1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_labels(((x1 - x0) / QUARTER).ceil() as usize + 1)
        .y_labels(7)
        .x_desc("crank angle [deg]")
        .y_desc(ylabel)
        .label_style((FAMILY, 17).into_font())
        .axis_desc_style((FAMILY, 19).into_font())
        .x_label_formatter(&|v| format!("{:.0}", v * QUARTER))
        .y_label_formatter(&|v| format_tick(*v))
        .light_line_style(RGBColor(245, 245, 245))
        .draw()
        .map_err(e)?;
    for c in curves {
        let style = c.color.stroke_width(3);
        let legend_style = style;
        // A single sample (a steady case) draws no line: mark it.
        if c.points.len() == 1 {
            let (x, y) = c.points[0];
            chart
                .draw_series(std::iter::once(Circle::new(
                    (x / QUARTER, y),
                    6,
                    c.color.filled(),
                )))
                .map_err(e)?;
        }
        let points = c.points.iter().map(|(x, y)| (x / QUARTER, *y));
        let anno = if c.dashed {
            chart
                .draw_series(DashedLineSeries::new(points, 10, 6, style))
                .map_err(e)?
        } else {
            chart
                .draw_series(LineSeries::new(points, style))
                .map_err(e)?
        };
        let dashed = c.dashed;
        anno.label(c.label.clone()).legend(move |(x, y)| {
            if dashed {
                PathElement::new(vec![(x, y), (x + 8, y)], legend_style)
            } else {
                PathElement::new(vec![(x, y), (x + 22, y)], legend_style)
            }
        });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .label_font((FAMILY, 17).into_font())
        .draw()
        .map_err(e)?;
    Ok(())
}

/// Ticks of e/c: one decimal, and no "-0.0".
fn format_unit_tick(v: f64) -> String {
    if v.abs() < 0.05 {
        "0".into()
    } else {
        format!("{v:.1}")
    }
}

/// Tick labels with as many digits as the magnitude needs.
fn format_tick(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.2e}")
    } else if a >= 100.0 {
        format!("{v:.0}")
    } else if a >= 10.0 {
        format!("{v:.1}")
    } else if a >= 0.1 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

fn draw_orbit(r: &CaseReport, path: &Path, size: u32) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let root = BitMapBackend::new(path, (size, size)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let c = r.geometry.radial_clearance;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("{}: journal orbit in the clearance circle", r.case_name),
            (FAMILY, 26).into_font(),
        )
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(70)
        .build_cartesian_2d(-1.1f64..1.1f64, -1.1f64..1.1f64)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_labels(11)
        .y_labels(11)
        .x_desc("e_x / c  (bearing frame)")
        .y_desc("e_y / c")
        .label_style((FAMILY, 17).into_font())
        .axis_desc_style((FAMILY, 20).into_font())
        .x_label_formatter(&|v| format_unit_tick(*v))
        .y_label_formatter(&|v| format_unit_tick(*v))
        .light_line_style(TRANSPARENT)
        .draw()
        .map_err(e)?;
    let circle = |radius: f64| -> Vec<(f64, f64)> {
        (0..=360)
            .map(|k| {
                let a = (k as f64).to_radians();
                (radius * a.cos(), radius * a.sin())
            })
            .collect()
    };
    chart
        .draw_series(LineSeries::new(circle(1.0), BLACK.stroke_width(2)))
        .map_err(e)?
        .label(format!("clearance circle, c = {:.1} µm", c * 1e6))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], BLACK.stroke_width(2)));
    for radius in [0.25, 0.5, 0.75] {
        chart
            .draw_series(DashedLineSeries::new(
                circle(radius),
                4,
                6,
                RGBColor(170, 170, 170).stroke_width(1),
            ))
            .map_err(e)?;
    }
    for m in &r.methods {
        let (Some(ex), Some(ey)) = (
            m.series(names::ECCENTRICITY_X),
            m.series(names::ECCENTRICITY_Y),
        ) else {
            continue;
        };
        let pts: Vec<(f64, f64)> = ex
            .values
            .iter()
            .zip(&ey.values)
            .map(|(x, y)| (x / c, y / c))
            .collect();
        let color = method_color(m.method);
        let style = color.stroke_width(3);
        let anno = if m.method == Method::Mobility {
            chart
                .draw_series(DashedLineSeries::new(pts.iter().copied(), 10, 6, style))
                .map_err(e)?
        } else {
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), style))
                .map_err(e)?
        };
        anno.label(m.method.to_string())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], style));
        let start = pts[0];
        let crank0 = m.crank_angle[0];
        chart
            .draw_series(std::iter::once(Circle::new(start, 7, color.filled())))
            .map_err(e)?
            .label(format!("{}: at crank angle {crank0:.0}°", m.method))
            .legend(move |(x, y)| Circle::new((x + 11, y), 6, color.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.9))
        .border_style(RGBColor(160, 160, 160))
        .label_font((FAMILY, 17).into_font())
        .draw()
        .map_err(e)?;
    root.present().map_err(e)
}
