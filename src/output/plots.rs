//! PNG plots of one case, after Yu & Sawicki \[YuSawicki2002\], Figs. 3 and 4, and the pictures every
//! engine-bearing code draws.
//!
//! `CASE_cycle.png` — six panels against crank angle, rigorous (solid blue) and mobility (dashed
//! red) overlaid where both methods have the quantity; inputs shared by both (loads, feed
//! pressure) solid in their own colours:
//!
//! ```text
//!   title; a red status line when a result is not periodic, stalled or failed
//!   (a) load components W_x, W_y [kN]      (b) feed pressure [MPa]
//!   (c) eccentricity ratio [–]             (d) minimum film thickness [µm]
//!   (e) flow rate: supply, side leakage    (f) power loss [W]
//!       [cm³/s]
//!   every panel: its legend in a strip above the data; x from 0 to the full cycle, ticks every
//!   90° including the last; TDC (crank 0° and every 360°) dotted; the feed window (feed
//!   pressure above its minimum) shaded
//! ```
//!
//! `CASE_orbit.png` — the journal-centre orbit e/c in a smooth clearance circle, bearing frame,
//! both methods: crank-angle labels every 30° (rigorous, else mobility), direction arrows, the
//! start (crank 0°) marked alike for both, the groove arcs on the circle, the direction of the
//! peak load, the legend beside the circle.
//!
//! `CASE_load.png` — the polar load diagram: the tip of the load vector (kN, bearing frame) over
//! the cycle, crank-angle labels every 30°, direction arrows.
//!
//! `CASE_film.png` (rigorous fields only) — film pressure and film content at the mid-plane over
//! (crank angle, θ): the classic picture of a cavitating dynamically loaded bearing.
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

use super::{
    CaseReport, Method, MethodResult, OutputError, OutputWriter, ParameterValue, names,
    write_atomically,
};

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
pub(crate) const FAMILY: &str = "sans-serif";

pub(crate) fn ensure_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FAMILY, FontStyle::Normal, FONT)
                .map_err(|_| "the embedded DejaVu Sans font could not be parsed".to_string())
        })
        .clone()
}

/// Writes `CASE_cycle.png`, `CASE_orbit.png`, `CASE_load.png` and, when the rigorous method
/// stored fields, `CASE_film.png`.
#[derive(Debug, Clone, Copy)]
pub struct PlotWriter {
    /// Size of the six-panel figure in pixels.
    pub cycle_size: (u32, u32),
    /// Size of the (square) orbit and load diagrams in pixels (a legend strip is added beside
    /// the orbit).
    pub orbit_size: u32,
    /// Size of the film map in pixels.
    pub film_size: (u32, u32),
}

impl Default for PlotWriter {
    fn default() -> Self {
        Self {
            cycle_size: (1500, 1560),
            orbit_size: 900,
            film_size: (1400, 1000),
        }
    }
}

/// Width of the legend strip beside the orbit.
pub const ORBIT_LEGEND_WIDTH: u32 = 340;

impl PlotWriter {
    /// Paths of the figures written for `report` in `dir`: cycle, orbit, load diagram, and the
    /// film map when the report has fields.
    ///
    /// A report with a deformable bearing (`elastic`) adds `CASE_elastic.png` (bore stresses and
    /// the deformed film along the surface); one with no method (only the deformable bearing)
    /// has only that figure.
    pub fn file_paths(report: &CaseReport, dir: &Path) -> Vec<PathBuf> {
        let mut v = Vec::new();
        if !report.methods.is_empty() {
            v.push(dir.join(format!("{}_cycle.png", report.case_name)));
            v.push(dir.join(format!("{}_orbit.png", report.case_name)));
            v.push(dir.join(format!("{}_load.png", report.case_name)));
            if film_fields(report).is_some() {
                v.push(dir.join(format!("{}_film.png", report.case_name)));
            }
        }
        if report.elastic.is_some() {
            v.push(Self::elastic_path(report, dir));
        }
        v
    }

    fn elastic_path(report: &CaseReport, dir: &Path) -> PathBuf {
        dir.join(format!("{}_elastic.png", report.case_name))
    }
}

impl OutputWriter for PlotWriter {
    fn name(&self) -> &'static str {
        "plots"
    }

    fn write(&self, report: &CaseReport, dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
        report.validate()?;
        let paths = Self::file_paths(report, dir);
        let plot_err = |path: &Path| {
            let path = path.to_path_buf();
            move |message: String| OutputError::Plot { path, message }
        };
        let Some(first) = paths.first() else {
            return Ok(paths);
        };
        ensure_font().map_err(plot_err(first))?;
        let ctx = FigureContext::of(report);
        if !report.methods.is_empty() {
            write_atomically(&paths[0], |tmp| {
                draw_cycle(report, &ctx, tmp, self.cycle_size).map_err(plot_err(&paths[0]))
            })?;
            write_atomically(&paths[1], |tmp| {
                draw_orbit(report, &ctx, tmp, self.orbit_size).map_err(plot_err(&paths[1]))
            })?;
            write_atomically(&paths[2], |tmp| {
                draw_load(report, &ctx, tmp, self.orbit_size).map_err(plot_err(&paths[2]))
            })?;
            if film_fields(report).is_some() {
                let path = &paths[3];
                write_atomically(path, |tmp| {
                    draw_film(report, &ctx, tmp, self.film_size).map_err(plot_err(path))
                })?;
            }
        }
        if let Some(e) = &report.elastic {
            let path = Self::elastic_path(report, dir);
            write_atomically(&path, |tmp| {
                draw_elastic(report, e, &ctx, tmp, self.film_size).map_err(plot_err(&path))
            })?;
        }
        Ok(paths)
    }
}

/// What the figures need beyond the series: the cycle length, the grooves, the feed window
/// and what to warn about.
struct FigureContext {
    /// Cycle length (deg): the crank grid's last angle plus one step (360 for a single sample).
    cycle: f64,
    /// Grooves: (centre angle, angular width) in rad, bearing frame.
    grooves: Vec<(f64, f64)>,
    /// Crank-angle intervals (deg) where the feed pressure is above its cycle minimum.
    feed_windows: Vec<(f64, f64)>,
    /// "rigorous: not periodic" and the like, for every method whose status is not "ok".
    warnings: Vec<String>,
}

impl FigureContext {
    fn of(r: &CaseReport) -> Self {
        let cycle = r
            .methods
            .iter()
            .map(|m| &m.crank_angle)
            .find(|c| c.len() >= 2)
            .map_or(360.0, |c| c[c.len() - 1] + (c[1] - c[0]));
        let number = |key: &str| {
            r.parameters
                .iter()
                .find(|p| p.key == key)
                .and_then(|p| match p.value {
                    ParameterValue::Number(v) => Some(v),
                    _ => None,
                })
        };
        let radius = number("radius").unwrap_or(r.geometry.radius);
        let grooves = (0..)
            .map_while(|i| {
                let centre = number(&format!("groove{i}_center_angle"))?;
                let length = number(&format!("groove{i}_circumferential_length"))?;
                Some((centre, length / radius))
            })
            .collect();
        let feed_windows = r
            .methods
            .iter()
            .find_map(|m| m.series(names::FEED_PRESSURE).map(|s| (m, s)))
            .map(|(m, s)| feed_windows(&m.crank_angle, &s.values, cycle))
            .unwrap_or_default();
        let warnings = Method::ALL
            .iter()
            .filter_map(|&m| {
                let status = r.status(m)?;
                (status != "ok").then(|| {
                    let short: String = status.chars().take(90).collect();
                    format!("{m}: {short}")
                })
            })
            .collect();
        Self {
            cycle,
            grooves,
            feed_windows,
            warnings,
        }
    }
}

/// Crank-angle intervals where `feed` is above its minimum by more than 1 % of its range (the
/// feed window of an intermittently fed bearing); none for a constant feed.
pub fn feed_windows(crank: &[f64], feed: &[f64], cycle: f64) -> Vec<(f64, f64)> {
    let (lo, hi) = feed
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) || crank.len() < 2 {
        return Vec::new();
    }
    let open = |v: f64| v > lo + 0.01 * (hi - lo);
    let step = crank[1] - crank[0];
    let mut out = Vec::new();
    let mut start: Option<f64> = None;
    for (c, v) in crank.iter().zip(feed) {
        match (open(*v), start) {
            (true, None) => start = Some((c - 0.5 * step).max(0.0)),
            (false, Some(s)) => {
                out.push((s, c - 0.5 * step));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, cycle));
    }
    out
}

/// Indices of the samples at whole multiples of `every` degrees of crank angle.
pub fn label_indices(crank: &[f64], every: f64) -> Vec<usize> {
    crank
        .iter()
        .enumerate()
        .filter(|(_, c)| {
            let r = (*c / every).round();
            (*c - r * every).abs() < 1e-6
        })
        .map(|(i, _)| i)
        .collect()
}

/// Style of a method's curves.
fn method_color(m: Method) -> RGBColor {
    match m {
        Method::Rigorous => RGBColor(31, 87, 180),
        Method::Mobility => RGBColor(205, 45, 40),
    }
}

const GREY: RGBColor = RGBColor(120, 120, 120);
const FEED_SHADE: RGBColor = RGBColor(255, 236, 200);
const WARN_RED: RGBColor = RGBColor(200, 20, 20);

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
/// them when `shared` (inputs such as the load: solid, one colour per series).
fn method_curves(
    r: &CaseReport,
    series: &[(&str, &str)],
    shared: bool,
) -> (Vec<Curve>, Option<String>) {
    let mut curves = Vec::new();
    let mut unit = None;
    for (k, (name, label)) in series.iter().enumerate() {
        for m in &r.methods {
            let dashed = !shared && m.method == Method::Mobility;
            let color = if shared {
                [RGBColor(40, 40, 40), RGBColor(20, 140, 70)][k % 2]
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

/// The figure's title, and under it in red what is wrong with a result (not periodic,
/// stalled steps, failed). Returns the area below.
fn title_block<'a>(
    root: &DrawingArea<BitMapBackend<'a>, Shift>,
    title: &str,
    ctx: &FigureContext,
) -> Result<DrawingArea<BitMapBackend<'a>, Shift>, String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let height = if ctx.warnings.is_empty() { 50 } else { 84 };
    let (top, body) = root.split_vertically(height);
    let (w, _) = top.dim_in_pixel();
    let font = (FAMILY, 28).into_font();
    let tw = top
        .estimate_text_size(title, &font.clone().into())
        .map_err(e)?
        .0;
    top.draw(&Text::new(
        title.to_string(),
        ((w as i32 - tw as i32) / 2, 10),
        font,
    ))
    .map_err(e)?;
    if !ctx.warnings.is_empty() {
        let line = format!("CAUTION: {}", ctx.warnings.join("; "));
        let font = (FAMILY, 22).into_font().color(&WARN_RED);
        let tw = top.estimate_text_size(&line, &font).map_err(e)?.0;
        top.draw(&Text::new(
            line,
            (((w as i32 - tw as i32) / 2).max(4), 50),
            font,
        ))
        .map_err(e)?;
    }
    Ok(body)
}

fn draw_cycle(
    r: &CaseReport,
    ctx: &FigureContext,
    path: &Path,
    size: (u32, u32),
) -> Result<(), String> {
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let styles: Vec<&str> = r
        .methods
        .iter()
        .map(|m| match m.method {
            Method::Rigorous => "rigorous (solid)",
            Method::Mobility => "mobility (dashed)",
        })
        .collect();
    let title = format!(
        "{}: {} against crank angle",
        r.case_name,
        styles.join(" and ")
    );
    let body = title_block(&root, &title, ctx)?;
    let panels = body.split_evenly((3, 2));
    let specs: [PanelSpec; 6] = [
        (
            "(a) Load components (input)",
            "load",
            vec![(names::LOAD_X, "W_x"), (names::LOAD_Y, "W_y")],
            true,
        ),
        (
            "(b) Feed pressure (input)",
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
        // A feed pressure that is zero all cycle is no feed: say so instead of a flat line.
        let no_feed = series[0].0 == names::FEED_PRESSURE
            && curves
                .iter()
                .all(|c| c.points.iter().all(|(_, y)| *y == 0.0));
        if no_feed && !curves.is_empty() {
            note_panel(area, title, "no feed pressure (no supplied groove)")?;
            continue;
        }
        draw_panel(area, title, &ylabel, &curves, ctx)?;
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

/// A panel with a title and a note instead of curves.
fn note_panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    title: &str,
    note: &str,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    area.draw(&Text::new(
        format!("{title}: {note}"),
        (40, 60),
        (FAMILY, 22).into_font(),
    ))
    .map_err(e)?;
    Ok(())
}

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mark {
    Line,
    Dashed,
    Dot,
    Patch,
}

/// A legend entry: label, colour, mark.
type LegendEntry = (String, RGBColor, Mark);

/// The sample of a legend entry, 30 px wide, centred on height `y` from `x`.
fn legend_mark(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    (x, y): (i32, i32),
    color: RGBColor,
    mark: Mark,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let style = color.stroke_width(3);
    match mark {
        Mark::Dashed => {
            for k in 0..3 {
                area.draw(&PathElement::new(
                    vec![(x + 11 * k, y), (x + 11 * k + 7, y)],
                    style,
                ))
                .map_err(e)?;
            }
        }
        Mark::Patch => area
            .draw(&Rectangle::new(
                [(x, y - 8), (x + 30, y + 8)],
                color.filled(),
            ))
            .map_err(e)?,
        Mark::Dot => area
            .draw(&Circle::new((x + 15, y), 7, color.filled()))
            .map_err(e)?,
        Mark::Line => area
            .draw(&PathElement::new(vec![(x, y), (x + 30, y)], style))
            .map_err(e)?,
    }
    Ok(())
}

/// A legend in a strip of its own (above the data, never on it): a sample and the label of
/// each entry, side by side.
fn legend_strip(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    entries: &[LegendEntry],
    x0: i32,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    // The largest font (17 px down to 12 px) at which every entry fits in the strip.
    let available = area.dim_in_pixel().0 as i32 - x0;
    let mut size = 17;
    let font = loop {
        let font = (FAMILY, size).into_font();
        let mut width = 0;
        for (label, _, _) in entries {
            width += 64
                + area
                    .estimate_text_size(label, &font.clone().into())
                    .map_err(e)?
                    .0 as i32;
        }
        if width <= available || size <= 12 {
            break font;
        }
        size -= 1;
    };
    let mut x = x0;
    for (label, color, mark) in entries {
        let y = 14;
        legend_mark(area, (x, y), *color, *mark)?;
        area.draw(&Text::new(label.clone(), (x + 38, y - 9), font.clone()))
            .map_err(e)?;
        x += 38
            + area
                .estimate_text_size(label, &font.clone().into())
                .map_err(e)?
                .0 as i32
            + 26;
    }
    Ok(())
}

/// The x axis of crank-angle charts runs in quarter turns (crank angle / 90°) so that plotters'
/// "nice" tick values (integers) fall on 0°, 90°, …, including the cycle's end; labels show
/// degrees. Plot at x = crank angle / `QUARTER`.
pub(crate) const QUARTER: f64 = 90.0;

/// A chart over crank angles `x` (degrees) and values `y` on `area`, its mesh drawn in the
/// project's style (cycle panels of the bearing cases, the mechanism's panels).
pub(crate) fn crank_angle_chart<'a, 'b>(
    area: &'a DrawingArea<BitMapBackend<'b>, Shift>,
    x: (f64, f64),
    y: (f64, f64),
    ylabel: &str,
) -> Result<
    ChartContext<
        'a,
        BitMapBackend<'b>,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    String,
> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let ((x0, x1), (y0, y1)) = (x, y);
    let mut chart = ChartBuilder::on(area)
        .x_label_area_size(48)
        .y_label_area_size(86)
        .build_cartesian_2d(x0 / QUARTER..x1 / QUARTER, y0..y1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_labels(((x1 - x0) / QUARTER).round() as usize + 1)
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
    Ok(chart)
}

/// One panel of the cycle figure: its title and legend strip above, then the feed window, TDC
/// and the curves; "not computed" when no method has the panel's series.
fn draw_panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    title: &str,
    ylabel: &str,
    curves: &[Curve],
    ctx: &FigureContext,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let area = area.margin(4, 8, 8, 16);
    if curves.is_empty() {
        return note_panel(&area, title, "not computed");
    }
    let (head, area) = area.split_vertically(64);
    head.draw(&Text::new(
        title.to_string(),
        (96, 2),
        (FAMILY, 22).into_font(),
    ))
    .map_err(e)?;
    draw_panel_legend(head, curves, ctx)?;
    let (x0, x1, y0, y1) = panel_ranges(curves, ctx);
    let mut chart = crank_angle_chart(&area, (x0, x1), (y0, y1), ylabel)?;
    draw_feed_and_tdc(&mut chart, ctx, (x0, x1), (y0, y1))?;
    draw_panel_curves(&mut chart, curves, ctx, x1)
}

/// The legend strip under a panel's title: one entry per curve, and the feed window's patch
/// when the feed opens and closes.
fn draw_panel_legend(
    head: DrawingArea<BitMapBackend<'_>, Shift>,
    curves: &[Curve],
    ctx: &FigureContext,
) -> Result<(), String> {
    let mut legend: Vec<LegendEntry> = curves
        .iter()
        .map(|c| {
            let mark = if c.dashed { Mark::Dashed } else { Mark::Line };
            (c.label.clone(), c.color, mark)
        })
        .collect();
    if !ctx.feed_windows.is_empty() {
        legend.push(("feed open".into(), FEED_SHADE, Mark::Patch));
    }
    let dims = head.dim_in_pixel();
    legend_strip(&head.shrink((0, 30), (dims.0, dims.1 - 30)), &legend, 96)
}

/// A panel's crank-angle span and padded value range `(x0, x1, y0, y1)`: the whole cycle, or a
/// 90° window centred on a single instant (a steady case).
fn panel_ranges(curves: &[Curve], ctx: &FigureContext) -> (f64, f64, f64, f64) {
    let (mut y0, mut y1) = (f64::MAX, f64::MIN);
    let (mut x0, mut x1) = (f64::MAX, f64::MIN);
    for (x, y) in curves.iter().flat_map(|c| c.points.iter()) {
        x0 = x0.min(*x);
        x1 = x1.max(*x);
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    let (y0, y1) = padded_range(y0, y1);
    // The whole cycle, 0 … cycle, whatever the samples cover (the periodic end point is not
    // stored); a single instant (steady case) is centred on a 90° window.
    let (x0, x1) = if x1 > x0 {
        (0.0, ctx.cycle)
    } else {
        (x0 - 45.0, x0 + 45.0)
    };
    (x0, x1, y0, y1)
}

/// Behind a panel's data: the feed window shaded, then TDC (crank 0° and every full turn)
/// dotted and labelled.
fn draw_feed_and_tdc(
    chart: &mut Chart2d<'_, '_>,
    ctx: &FigureContext,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    for (a, b) in &ctx.feed_windows {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(a / QUARTER, y0), (b / QUARTER, y1)],
                FEED_SHADE.filled(),
            )))
            .map_err(e)?;
    }
    let mut tdc = 0.0;
    while tdc <= x1 + 1e-9 {
        if tdc >= x0 {
            chart
                .draw_series(DashedLineSeries::new(
                    [(tdc / QUARTER, y0), (tdc / QUARTER, y1)],
                    3,
                    5,
                    GREY.stroke_width(2),
                ))
                .map_err(e)?;
            if tdc < x1 - 1e-9 {
                chart
                    .draw_series(std::iter::once(Text::new(
                        "TDC",
                        (tdc / QUARTER + 0.02, y1),
                        (FAMILY, 15).into_font().color(&GREY),
                    )))
                    .map_err(e)?;
            }
        }
        tdc += 360.0;
    }
    Ok(())
}

/// A panel's curves, closed over the cycle when the panel spans it (`x1` the cycle's end); a
/// single sample (a steady case) marked by a dot.
fn draw_panel_curves(
    chart: &mut Chart2d<'_, '_>,
    curves: &[Curve],
    ctx: &FigureContext,
    x1: f64,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    for c in curves {
        let style = c.color.stroke_width(3);
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
        // Close the periodic curve: the sample at 0 again at the cycle's end.
        let mut pts: Vec<(f64, f64)> = c.points.iter().map(|(x, y)| (x / QUARTER, *y)).collect();
        if c.points.len() > 1 && x1 == ctx.cycle {
            pts.push((ctx.cycle / QUARTER, c.points[0].1));
        }
        if c.dashed {
            chart
                .draw_series(DashedLineSeries::new(pts, 10, 6, style))
                .map_err(e)?;
        } else {
            chart.draw_series(LineSeries::new(pts, style)).map_err(e)?;
        }
    }
    Ok(())
}

/// Ticks of e/c: one decimal, and no "-0.0".
pub(crate) fn format_unit_tick(v: f64) -> String {
    if v.abs() < 0.05 {
        "0".into()
    } else {
        format!("{v:.1}")
    }
}

/// Tick labels with as many digits as the magnitude needs.
pub(crate) fn format_tick(v: f64) -> String {
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

/// Polyline of a circle of `radius` (data units), fine enough to look round at any size.
pub(crate) fn circle_points(radius: f64) -> Vec<(f64, f64)> {
    (0..=2048)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 2048.0;
            (radius * a.cos(), radius * a.sin())
        })
        .collect()
}

/// An arrow head at `at`, pointing along `dir` (data units), `size` long.
pub(crate) fn arrow_head(at: (f64, f64), dir: (f64, f64), size: f64) -> Option<Vec<(f64, f64)>> {
    let n = dir.0.hypot(dir.1);
    if n.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let (ux, uy) = (dir.0 / n, dir.1 / n);
    let (px, py) = (-uy, ux);
    let tip = (at.0 + 0.5 * size * ux, at.1 + 0.5 * size * uy);
    let back = (at.0 - 0.5 * size * ux, at.1 - 0.5 * size * uy);
    Some(vec![
        tip,
        (back.0 + 0.45 * size * px, back.1 + 0.45 * size * py),
        (back.0 - 0.45 * size * px, back.1 - 0.45 * size * py),
    ])
}

type Chart2d<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// A closed periodic path with crank-angle labels every 30° (when `labels`), dots there, and
/// arrows at every 90° showing the direction of travel.
fn draw_locus(
    chart: &mut Chart2d<'_, '_>,
    pts: &[(f64, f64)],
    crank: &[f64],
    color: RGBColor,
    dashed: bool,
    labels: bool,
    scale: f64,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let style = color.stroke_width(3);
    let mut closed = pts.to_vec();
    if pts.len() > 1 {
        closed.push(pts[0]);
    }
    if dashed {
        chart
            .draw_series(DashedLineSeries::new(closed, 10, 6, style))
            .map_err(e)?;
    } else {
        chart
            .draw_series(LineSeries::new(closed, style))
            .map_err(e)?;
    }
    let n = pts.len();
    for i in label_indices(crank, 30.0) {
        chart
            .draw_series(std::iter::once(Circle::new(pts[i], 4, color.filled())))
            .map_err(e)?;
        if labels {
            // Outward from the origin, a little off the path.
            let (x, y) = pts[i];
            let r = x.hypot(y).max(1e-12);
            let off = 0.045 * scale;
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{:.0}°", crank[i]),
                    (x + off * x / r, y + off * y / r),
                    (FAMILY, 15).into_font().color(&color),
                )))
                .map_err(e)?;
        }
    }
    if n > 2 {
        for i in label_indices(crank, 90.0) {
            let next = pts[(i + 1) % n];
            let prev = pts[(i + n - 1) % n];
            let dir = (next.0 - prev.0, next.1 - prev.1);
            let at = (0.5 * (pts[i].0 + next.0), 0.5 * (pts[i].1 + next.1));
            if let Some(head) = arrow_head(at, dir, 0.045 * scale) {
                chart
                    .draw_series(std::iter::once(Polygon::new(head, color.filled())))
                    .map_err(e)?;
            }
        }
    }
    Ok(())
}

/// The legend of the orbit and load diagrams, in its own strip beside the chart.
fn side_legend(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    entries: &[LegendEntry],
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let font = (FAMILY, 17).into_font();
    for (k, (label, color, mark)) in entries.iter().enumerate() {
        let y = 120 + 34 * k as i32;
        legend_mark(area, (10, y), *color, *mark)?;
        area.draw(&Text::new(label.clone(), (50, y - 9), font.clone()))
            .map_err(e)?;
    }
    Ok(())
}

/// `CASE_orbit.png`: the clearance circle with its grooves and the peak load's direction, every
/// method's orbit on it, and the legend beside the circle.
fn draw_orbit(r: &CaseReport, ctx: &FigureContext, path: &Path, size: u32) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    // The title block on top of a square chart area, so that the circle is round.
    let title_height = if ctx.warnings.is_empty() { 50 } else { 84 };
    let root = BitMapBackend::new(path, (size + ORBIT_LEGEND_WIDTH, size + title_height))
        .into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let c = r.geometry.radial_clearance;
    let body = title_block(
        &root,
        &format!("{}: journal orbit in the clearance circle", r.case_name),
        ctx,
    )?;
    let (plot, legend_area) = body.split_horizontally(size);
    let mut chart = orbit_chart(&plot)?;
    let mut legend = vec![(
        format!("clearance circle, c = {:.1} µm", c * 1e6),
        BLACK,
        Mark::Line,
    )];
    draw_clearance_circles(&mut chart)?;
    legend.extend(draw_grooves(&mut chart, &ctx.grooves)?);
    legend.extend(draw_peak_load_direction(&mut chart, r)?);
    legend.extend(draw_method_orbits(&mut chart, r, c)?);
    legend.push(("crank 0° (start); dots every 30°".into(), BLACK, Mark::Dot));
    side_legend(&legend_area, &legend)?;
    root.present().map_err(e)
}

/// The orbit's axes, e / c both ways from −1.15 to 1.15, with their ticks and labels.
fn orbit_chart<'a, 'b>(
    plot: &'a DrawingArea<BitMapBackend<'b>, Shift>,
) -> Result<Chart2d<'a, 'b>, String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let mut chart = ChartBuilder::on(plot)
        .margin(16)
        .x_label_area_size(64)
        .y_label_area_size(64)
        .build_cartesian_2d(-1.15f64..1.15f64, -1.15f64..1.15f64)
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
    Ok(chart)
}

/// The clearance circle (e = c) and dashed rings at e / c = 0.25, 0.5, 0.75.
fn draw_clearance_circles(chart: &mut Chart2d<'_, '_>) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    chart
        .draw_series(LineSeries::new(circle_points(1.0), BLACK.stroke_width(2)))
        .map_err(e)?;
    for radius in [0.25, 0.5, 0.75] {
        chart
            .draw_series(DashedLineSeries::new(
                circle_points(radius),
                4,
                6,
                RGBColor(170, 170, 170).stroke_width(1),
            ))
            .map_err(e)?;
    }
    Ok(())
}

/// The grooves (centre, angular width in rad) as thick arcs on the circle; their legend entry
/// when there is one.
fn draw_grooves(
    chart: &mut Chart2d<'_, '_>,
    grooves: &[(f64, f64)],
) -> Result<Option<LegendEntry>, String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let groove_color = RGBColor(20, 140, 70);
    for (centre, width) in grooves {
        let arc: Vec<(f64, f64)> = (0..=64)
            .map(|k| {
                let a = centre - 0.5 * width + width * k as f64 / 64.0;
                (1.02 * a.cos(), 1.02 * a.sin())
            })
            .collect();
        chart
            .draw_series(LineSeries::new(arc, groove_color.stroke_width(9)))
            .map_err(e)?;
    }
    Ok((!grooves.is_empty()).then(|| ("groove".into(), groove_color, Mark::Line)))
}

/// An arrow from the centre in the direction of the largest load of the first method that has
/// the load, and its legend entry (with the crank angle of the peak); nothing without a load.
fn draw_peak_load_direction(
    chart: &mut Chart2d<'_, '_>,
    r: &CaseReport,
) -> Result<Option<LegendEntry>, String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let Some((m, wx, wy)) = r
        .methods
        .iter()
        .find_map(|m| Some((m, m.series(names::LOAD_X)?, m.series(names::LOAD_Y)?)))
    else {
        return Ok(None);
    };
    let Some((k, _)) = wx
        .values
        .iter()
        .zip(&wy.values)
        .map(|(x, y)| x.hypot(*y))
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
    else {
        return Ok(None);
    };
    let (x, y) = (wx.values[k], wy.values[k]);
    let n = x.hypot(y);
    if n > 0.0 {
        let tip = (0.85 * x / n, 0.85 * y / n);
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 0.0), tip],
                GREY.stroke_width(3),
            )))
            .map_err(e)?;
        if let Some(head) = arrow_head(tip, (x, y), 0.08) {
            chart
                .draw_series(std::iter::once(Polygon::new(head, GREY.filled())))
                .map_err(e)?;
        }
        return Ok(Some((
            format!("peak load direction ({:.0}°)", m.crank_angle[k]),
            GREY,
            Mark::Line,
        )));
    }
    Ok(None)
}

/// Every method's orbit in e / c (crank-angle labels on the rigorous one, else the first), its
/// start at crank 0° marked alike for all, and a legend entry per method drawn.
fn draw_method_orbits(
    chart: &mut Chart2d<'_, '_>,
    r: &CaseReport,
    c: f64,
) -> Result<Vec<LegendEntry>, String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let mut legend = Vec::new();
    let labelled = r
        .methods
        .iter()
        .position(|m| m.method == Method::Rigorous)
        .unwrap_or(0);
    for (k, m) in r.methods.iter().enumerate() {
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
        let dashed = m.method == Method::Mobility;
        draw_locus(
            chart,
            &pts,
            &m.crank_angle,
            color,
            dashed,
            k == labelled,
            1.0,
        )?;
        // The start (crank 0°) marked alike for every method.
        chart
            .draw_series(std::iter::once(Circle::new(pts[0], 8, color.filled())))
            .map_err(e)?;
        chart
            .draw_series(std::iter::once(Circle::new(
                pts[0],
                8,
                BLACK.stroke_width(1),
            )))
            .map_err(e)?;
        let mark = if dashed { Mark::Dashed } else { Mark::Line };
        legend.push((m.method.to_string(), color, mark));
    }
    Ok(legend)
}

/// The polar load diagram: the load vector's tip over the cycle.
fn draw_load(r: &CaseReport, ctx: &FigureContext, path: &Path, size: u32) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let title_height = if ctx.warnings.is_empty() { 50 } else { 84 };
    let root = BitMapBackend::new(path, (size, size + title_height)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let body = title_block(
        &root,
        &format!("{}: polar load diagram (load on the journal)", r.case_name),
        ctx,
    )?;
    let Some((m, wx, wy)) = r
        .methods
        .iter()
        .find_map(|m| Some((m, m.series(names::LOAD_X)?, m.series(names::LOAD_Y)?)))
    else {
        return note_panel(&body, "load", "not in the results");
    };
    let pts: Vec<(f64, f64)> = wx
        .values
        .iter()
        .zip(&wy.values)
        .map(|(x, y)| (x * 1e-3, y * 1e-3))
        .collect();
    let reach = pts
        .iter()
        .map(|(x, y)| x.hypot(*y))
        .fold(0.0, f64::max)
        .max(1e-9)
        * 1.15;
    let mut chart = load_chart(&body, reach)?;
    draw_locus(
        &mut chart,
        &pts,
        &m.crank_angle,
        RGBColor(40, 40, 40),
        false,
        true,
        reach / 1.15,
    )?;
    chart
        .draw_series(std::iter::once(Circle::new(
            pts[0],
            8,
            RGBColor(40, 40, 40).filled(),
        )))
        .map_err(e)?;
    chart
        .draw_series(std::iter::once(Text::new(
            "crank angle labels every 30°, ● at 0°, arrows: direction of travel",
            (-reach * 0.97, -reach * 0.97),
            (FAMILY, 16).into_font().color(&GREY),
        )))
        .map_err(e)?;
    root.present().map_err(e)
}

/// The load diagram's axes, W_x and W_y in kN from −`reach` to `reach`, with the axis lines
/// through the origin.
fn load_chart<'a, 'b>(
    body: &'a DrawingArea<BitMapBackend<'b>, Shift>,
    reach: f64,
) -> Result<Chart2d<'a, 'b>, String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let mut chart = ChartBuilder::on(body)
        .margin(16)
        .x_label_area_size(72)
        .y_label_area_size(72)
        .build_cartesian_2d(-reach..reach, -reach..reach)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_labels(9)
        .y_labels(9)
        .x_desc("W_x [kN]  (bearing frame)")
        .y_desc("W_y [kN]")
        .label_style((FAMILY, 17).into_font())
        .axis_desc_style((FAMILY, 20).into_font())
        .x_label_formatter(&|v| format_tick(*v))
        .y_label_formatter(&|v| format_tick(*v))
        .light_line_style(RGBColor(240, 240, 240))
        .draw()
        .map_err(e)?;
    for axis in [[(-reach, 0.0), (reach, 0.0)], [(0.0, -reach), (0.0, reach)]] {
        chart
            .draw_series(std::iter::once(PathElement::new(
                axis.to_vec(),
                GREY.stroke_width(1),
            )))
            .map_err(e)?;
    }
    Ok(chart)
}

/// The deformable bearing along the film surface against θ (bearing frame): the stresses on the
/// housing bore (σ_r, σ_θ, σ_z, von Mises, with −p̄, which σ_r equals where the film presses) and
/// below it the deformed film thickness h and the gap change g.
fn draw_elastic(
    r: &CaseReport,
    el: &super::ElasticReport,
    ctx: &FigureContext,
    path: &Path,
    size: (u32, u32),
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let title_height = if ctx.warnings.is_empty() { 50 } else { 84 };
    let root = BitMapBackend::new(path, (size.0, size.1 + title_height)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let body = title_block(
        &root,
        &format!(
            "{}: deformable bearing, bore stresses and film",
            r.case_name
        ),
        ctx,
    )?;
    let (top, bottom) = body.split_vertically((size.1 as f64 * 0.58) as u32);
    let deg: Vec<f64> = el.angle.iter().map(|a| a.to_degrees()).collect();
    let (stresses, minus_p, film) = elastic_curves(el);
    for (area, curves, extra, y_desc) in [
        (
            &top,
            &stresses,
            Some(&minus_p),
            "stress on the housing bore [MPa]",
        ),
        (&bottom, &film, None, "film [µm]"),
    ] {
        draw_elastic_panel(area, &deg, curves, extra, y_desc)?;
    }
    root.present().map_err(e)
}

/// A curve against θ: legend label, values in display units, colour.
type ThetaCurve = (&'static str, Vec<f64>, RGBColor);

/// The elastic figure's curves in display units: the bore stresses [MPa], −p̄ [MPa] (empty
/// without the pressure) and the film h, g [µm]; a series the report lacks is left out.
fn elastic_curves(el: &super::ElasticReport) -> (Vec<ThetaCurve>, Vec<f64>, Vec<ThetaCurve>) {
    let get = |name: &str| el.series(name).map(|s| s.values.clone());
    let mpa = |v: Vec<f64>| v.into_iter().map(|x| x * 1e-6).collect::<Vec<_>>();
    let um = |v: Vec<f64>| v.into_iter().map(|x| x * 1e6).collect::<Vec<_>>();
    let stresses: Vec<ThetaCurve> = [
        ("σ_r", "bore_radial_stress", RGBColor(200, 30, 30)),
        ("σ_θ", "bore_hoop_stress", RGBColor(30, 90, 200)),
        ("σ_z", "bore_axial_stress", RGBColor(30, 150, 60)),
        ("von Mises", "bore_von_mises_stress", RGBColor(40, 40, 40)),
    ]
    .into_iter()
    .filter_map(|(label, name, color)| Some((label, mpa(get(name)?), color)))
    .collect();
    let minus_p: Vec<f64> = get("surface_pressure")
        .map(|v| v.into_iter().map(|x| -x * 1e-6).collect())
        .unwrap_or_default();
    let film: Vec<ThetaCurve> = [
        ("h (deformed film)", "film_thickness", RGBColor(30, 90, 200)),
        ("g (gap change)", "gap_change", RGBColor(200, 120, 20)),
    ]
    .into_iter()
    .filter_map(|(label, name, color)| Some((label, um(get(name)?), color)))
    .collect();
    (stresses, minus_p, film)
}

/// One panel of the elastic figure: `curves` against θ over 0 … 360°, the dashed `extra` (−p̄)
/// behind them when given, and the legend in the lower left; a note when nothing is finite.
fn draw_elastic_panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    deg: &[f64],
    curves: &[ThetaCurve],
    extra: Option<&Vec<f64>>,
    y_desc: &str,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let all = curves
        .iter()
        .flat_map(|c| c.1.iter())
        .chain(extra.into_iter().flatten())
        .copied()
        .filter(|v| v.is_finite());
    let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !(lo.is_finite() && hi.is_finite()) {
        return note_panel(area, y_desc, "not in the results");
    }
    let (lo, hi) = padded_range(lo, hi);
    let mut chart = ChartBuilder::on(area)
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(86)
        .build_cartesian_2d(0.0..360.0, lo..hi)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_labels(13)
        .y_labels(8)
        .x_desc("θ [°] (bearing frame, from +x towards +y)")
        .y_desc(y_desc)
        .label_style((FAMILY, 17).into_font())
        .axis_desc_style((FAMILY, 20).into_font())
        .x_label_formatter(&|v| format_tick(*v))
        .y_label_formatter(&|v| format_tick(*v))
        .light_line_style(RGBColor(240, 240, 240))
        .draw()
        .map_err(e)?;
    if let Some(p) = extra.filter(|p| !p.is_empty()) {
        chart
            .draw_series(DashedLineSeries::new(
                deg.iter().copied().zip(p.iter().copied()),
                8,
                5,
                RGBColor(150, 150, 150).stroke_width(2),
            ))
            .map_err(e)?
            .label("−p (film pressure, mean over the length)")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], RGBColor(150, 150, 150)));
    }
    for (label, values, color) in curves.iter() {
        let color = *color;
        chart
            .draw_series(LineSeries::new(
                deg.iter().copied().zip(values.iter().copied()),
                color.stroke_width(3),
            ))
            .map_err(e)?
            .label(*label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(3))
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FAMILY, 18).into_font())
        .position(SeriesLabelPosition::LowerLeft)
        .draw()
        .map_err(e)?;
    Ok(())
}

/// The rigorous fields if the report has them: (crank angles, θ, mid-plane pressure [k][i],
/// mid-plane film content [k][i]).
type MidPlane = (Vec<f64>, Vec<f64>, Vec<Vec<f64>>, Vec<Vec<f64>>);

fn film_fields(r: &CaseReport) -> Option<MidPlane> {
    let f = r.methods.iter().find_map(|m| m.fields.as_ref())?;
    let p = f.fields.iter().find(|x| x.name == names::PRESSURE)?;
    let content = f.fields.iter().find(|x| x.name == names::FILM_CONTENT)?;
    if f.crank_angle.len() < 2 || f.theta.len() < 3 {
        return None;
    }
    let mid = f.z.len() / 2;
    let slice = |a: &ndarray::Array3<f64>| -> Vec<Vec<f64>> {
        (0..f.crank_angle.len())
            .map(|k| (0..f.theta.len()).map(|i| a[[k, i, mid]]).collect())
            .collect()
    };
    Some((
        f.crank_angle.clone(),
        f.theta.clone(),
        slice(&p.values),
        slice(&content.values),
    ))
}

/// A colour of the `viridis`-like ramp for t in [0, 1].
fn ramp(t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let stops = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let x = t * (stops.len() - 1) as f64;
    let i = (x.floor() as usize).min(stops.len() - 2);
    let f = x - i as f64;
    let (a, b) = (stops[i], stops[i + 1]);
    let mix = |p: f64, q: f64| (p + f * (q - p)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Film pressure and film content at the mid-plane over (crank angle, θ).
fn draw_film(
    r: &CaseReport,
    ctx: &FigureContext,
    path: &Path,
    size: (u32, u32),
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let body = title_block(
        &root,
        &format!(
            "{}: film at the mid-plane over the cycle (rigorous)",
            r.case_name
        ),
        ctx,
    )?;
    let Some((crank, theta, pressure, content)) = film_fields(r) else {
        return note_panel(&body, "film", "no stored fields");
    };
    let panels = body.split_evenly((2, 1));
    for (area, (name, unit, values, scale)) in panels.iter().zip([
        ("film pressure", "MPa", &pressure, 1e-6),
        (
            "film content (1 = full film, < 1 cavitated)",
            "–",
            &content,
            1.0,
        ),
    ]) {
        let (main, bar) = area.split_horizontally(area.dim_in_pixel().0 - 150);
        let (lo, hi) = values
            .iter()
            .flatten()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v * scale), b.max(v * scale))
            });
        let hi = if hi > lo { hi } else { lo + 1.0 };
        let map = FilmMap {
            crank: &crank,
            n_theta: theta.len(),
            values,
            scale,
            range: (lo, hi),
        };
        draw_film_map(&main, name, &map, ctx)?;
        draw_colour_bar(&bar, unit, (lo, hi))?;
    }
    root.present().map_err(e)
}

/// One mid-plane field of the film figure over (crank angle, θ), scaled for display.
struct FilmMap<'a> {
    /// Crank angles of the snapshots (deg), evenly spaced.
    crank: &'a [f64],
    /// Nodes around, evenly spaced from θ = 0.
    n_theta: usize,
    /// Values [snapshot][node], SI.
    values: &'a [Vec<f64>],
    /// Display scale of the values.
    scale: f64,
    /// Colour range (display units): low and high ends of the ramp.
    range: (f64, f64),
}

/// A field's map over (crank angle, θ): axes in quarter turns and one coloured cell per
/// (instant, node).
fn draw_film_map(
    main: &DrawingArea<BitMapBackend<'_>, Shift>,
    name: &str,
    map: &FilmMap<'_>,
    ctx: &FigureContext,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let (crank, values, scale, (lo, hi)) = (map.crank, map.values, map.scale, map.range);
    let dc = crank[1] - crank[0];
    let dth = 360.0 / map.n_theta as f64;
    let mut chart = ChartBuilder::on(main)
        .caption(name, (FAMILY, 22).into_font())
        .margin(10)
        .x_label_area_size(48)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..ctx.cycle / 90.0, 0.0..4.0)
        .map_err(e)?;
    // Both axes in quarter turns so that the ticks fall on 0°, 90°, … (crank angle up to
    // the cycle, θ up to 360°).
    chart
        .configure_mesh()
        .x_labels((ctx.cycle / 90.0).round() as usize + 1)
        .y_labels(5)
        .x_desc("crank angle [deg]")
        .y_desc("θ [deg] from +x")
        .label_style((FAMILY, 16).into_font())
        .axis_desc_style((FAMILY, 18).into_font())
        .x_label_formatter(&|v| format!("{:.0}", v * 90.0))
        .y_label_formatter(&|v| format!("{:.0}", v * 90.0))
        .disable_mesh()
        .draw()
        .map_err(e)?;
    // One cell per (instant, node), centred on both; the periodic wrap fills the edges: the
    // instant at 0° again at the cycle's end, the node at θ = 0 again at 360°.
    let q = 90.0;
    let mut cells = Vec::new();
    let mut instants: Vec<(f64, &Vec<f64>)> = crank.iter().copied().zip(values.iter()).collect();
    if crank[0] == 0.0 {
        instants.push((ctx.cycle, &values[0]));
    }
    for (c, row) in instants {
        let (c0, c1) = ((c - 0.5 * dc).max(0.0), (c + 0.5 * dc).min(ctx.cycle));
        for i in 0..=row.len() {
            let v = row[i % row.len()];
            let t = i as f64 * dth;
            let (t0, t1) = ((t - 0.5 * dth).max(0.0), (t + 0.5 * dth).min(360.0));
            cells.push(Rectangle::new(
                [(c0 / q, t0 / q), (c1 / q, t1 / q)],
                ramp((v * scale - lo) / (hi - lo)).filled(),
            ));
        }
    }
    chart.draw_series(cells).map_err(e)?;
    Ok(())
}

/// The colour bar beside a film map: the ramp from `lo` to `hi` with its ticks in `unit`.
fn draw_colour_bar(
    bar: &DrawingArea<BitMapBackend<'_>, Shift>,
    unit: &str,
    (lo, hi): (f64, f64),
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let mut cb = ChartBuilder::on(bar)
        .margin_top(40)
        .margin_bottom(58)
        .margin_right(10)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(e)?;
    cb.configure_mesh()
        .disable_x_axis()
        .disable_mesh()
        .y_labels(6)
        .y_desc(unit)
        .label_style((FAMILY, 15).into_font())
        .y_label_formatter(&|v| format_tick(*v))
        .draw()
        .map_err(e)?;
    cb.draw_series((0..100).map(|k| {
        let a = lo + (hi - lo) * k as f64 / 100.0;
        let b = lo + (hi - lo) * (k + 1) as f64 / 100.0;
        Rectangle::new([(0.0, a), (1.0, b)], ramp(k as f64 / 99.0).filled())
    }))
    .map_err(e)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn feed_windows_cover_the_open_samples() {
        let crank: Vec<f64> = (0..36).map(|k| 10.0 * k as f64).collect();
        // Open from 30° to 80°, and again from 330° to the cycle's end.
        let feed: Vec<f64> = crank
            .iter()
            .map(|c| {
                if (30.0..=80.0).contains(c) || *c >= 330.0 {
                    2e5
                } else {
                    0.0
                }
            })
            .collect();
        assert_eq!(
            feed_windows(&crank, &feed, 360.0),
            vec![(25.0, 85.0), (325.0, 360.0)]
        );
        assert!(feed_windows(&crank, &vec![2e5; 36], 360.0).is_empty());
    }

    #[test]
    fn labels_fall_on_whole_multiples() {
        let crank: Vec<f64> = (0..72).map(|k| 5.0 * k as f64).collect();
        assert_eq!(label_indices(&crank, 90.0), vec![0, 18, 36, 54]);
        assert_eq!(label_indices(&crank, 30.0).len(), 12);
    }
}
