//! Error against render time: one progressive render, read back at sample counts 1, 2, 4, … and
//! compared with a reference after each. Render time counts the passes only (each synchronised with
//! the device), not the read-backs and comparisons in between, so the curve is what a render of that
//! length would have cost.
use crate::backend::{self, Backend, BackendChoice, GpuSelection};
use crate::output::compare::compare;
use crate::output::film::Film;
use crate::prepare::buffers::SceneBuffers;
use crate::render::passes::{render_observed, PassObserver};
use anyhow::{bail, Context, Result};
use caustic_kernel::layout::SAMPLER_INDEPENDENT;
use std::path::Path;

/// One point of the curve.
#[derive(Clone, Copy, Debug)]
pub struct ConvergencePoint {
    pub spp: u32,
    pub seconds: f64,
    pub rmse: f64,
    pub rel_mse: f64,
    pub luminance_ratio: f64,
    /// The error against the truth, where the reference has a variance (`render --variance`): `rmse`²
    /// and `rel_mse` less the reference's own noise (`compare::ReferenceNoise`). An estimate, so it
    /// may fall below zero once the render is as good as the reference; it lets a curve be followed
    /// past the reference's noise floor.
    pub net_mse: Option<f64>,
    pub net_rel_mse: Option<f64>,
}

impl ConvergencePoint {
    /// The point of an image at `spp` after `seconds`, from its comparison with the reference.
    pub fn of(spp: u32, seconds: f64, c: &crate::output::compare::Comparison) -> ConvergencePoint {
        ConvergencePoint {
            spp,
            seconds,
            rmse: c.rmse,
            rel_mse: c.rel_mse,
            luminance_ratio: c.luminance_ratio,
            net_mse: c.reference_noise.map(|n| c.rmse * c.rmse - n.mse),
            net_rel_mse: c.reference_noise.map(|n| c.rel_mse - n.rel_mse),
        }
    }
}

/// Sample counts at which the image is compared: powers of two up to `max_spp`, and `max_spp`.
pub fn checkpoints(max_spp: u32) -> Vec<u32> {
    let mut c: Vec<u32> = (0..32).map(|k| 1u32 << k).take_while(|&s| s < max_spp).collect();
    c.push(max_spp);
    c
}

/// Renders up to `max_spp` and measures the error against `reference` at every checkpoint. The
/// independent sampler is used whatever the scene asks: stratified strata laid out for the full
/// count would cover only part of each pixel at the earlier checkpoints.
pub fn measure(
    backend: &mut dyn Backend,
    buffers: &SceneBuffers,
    reference: &Film,
    max_spp: u32,
    seed: u32,
) -> Result<Vec<ConvergencePoint>> {
    if max_spp == 0 {
        bail!("the sample budget must be at least 1");
    }
    if (reference.width, reference.height) != (buffers.params.width, buffers.params.height) {
        bail!(
            "the reference is {}×{} but the render is {}×{}",
            reference.width,
            reference.height,
            buffers.params.width,
            buffers.params.height
        );
    }
    let mut buffers = buffers.clone();
    buffers.params.sampler = SAMPLER_INDEPENDENT;
    let stops = checkpoints(max_spp);
    let mut curve = Curve {
        stops: &stops,
        reference,
        size: (buffers.params.width, buffers.params.height),
        points: Vec::new(),
    };
    render_observed(backend, &buffers, 0, max_spp, seed, &stops, &mut curve)?;
    Ok(curve.points)
}

/// Refuses a reference (the file `reference_name`) of another size than the render of `buffers`
/// (the scene `scene_name`), before any backend starts.
pub fn check_reference_size(
    reference: &Film,
    reference_name: &Path,
    buffers: &SceneBuffers,
    scene_name: &Path,
) -> Result<()> {
    let (width, height) = (buffers.params.width, buffers.params.height);
    if (reference.width, reference.height) != (width, height) {
        bail!(
            "{} is {}×{} but {} renders {width}×{height}",
            reference_name.display(),
            reference.width,
            reference.height,
            scene_name.display()
        );
    }
    Ok(())
}

/// One curve as `caustic convergence` measures it: a one-sample warm-up (pipeline compilation,
/// caches) on a backend of its own, untimed, then `measure` on a new backend. Returns that
/// backend's description and the points.
pub fn measure_warmed_up(
    choice: BackendChoice,
    gpus: &GpuSelection,
    buffers: &SceneBuffers,
    reference: &Film,
    max_spp: u32,
    seed: u32,
) -> Result<(String, Vec<ConvergencePoint>)> {
    let mut warm_up = backend::create_on(choice, gpus, buffers)?;
    crate::render::passes::render(warm_up.as_mut(), buffers, 1, seed.wrapping_add(1), |_| {})?;
    let mut backend = backend::create_on(choice, gpus, buffers)?;
    let points = measure(backend.as_mut(), buffers, reference, max_spp, seed)?;
    Ok((backend.describe(), points))
}

/// Compares the image with the reference at each stop.
struct Curve<'a> {
    stops: &'a [u32],
    reference: &'a Film,
    size: (u32, u32),
    points: Vec<ConvergencePoint>,
}

impl PassObserver for &mut Curve<'_> {
    fn at_rest(
        &mut self,
        done: u32,
        seconds: f64,
        backend: &mut dyn Backend,
    ) -> Result<std::ops::ControlFlow<()>> {
        if self.stops.contains(&done) {
            let film = Film::from_accum(self.size.0, self.size.1, &backend.read_accum()?);
            let c = compare(&film, self.reference, 0.0)?;
            self.points.push(ConvergencePoint::of(done, seconds, &c));
        }
        Ok(std::ops::ControlFlow::Continue(()))
    }

    /// The curve reads the image alone: passes grow as a render's without `--variance` do.
    fn needs_variance(&self) -> bool {
        false
    }
}

/// Another renderer's curve: the renders a CSV lists (a header, then `spp,seconds,image` rows, each
/// image's path relative to the CSV's folder), each compared with `reference` as caustic's own
/// points are. Errors name the file and line.
pub fn peer_curve(csv: &Path, reference: &Film) -> Result<Vec<ConvergencePoint>> {
    let text = std::fs::read_to_string(csv).with_context(|| format!("cannot read {}", csv.display()))?;
    let dir = csv.parent().unwrap_or(Path::new("."));
    let mut points = Vec::new();
    for (number, line) in text.lines().enumerate().skip(1).filter(|(_, l)| !l.trim().is_empty()) {
        let at = || format!("{}:{}", csv.display(), number + 1);
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let [spp, seconds, image] = fields[..] else {
            bail!("{}: expected spp,seconds,image, found {line:?}", at());
        };
        let spp: u32 = spp.parse().with_context(|| format!("{}: spp {spp:?}", at()))?;
        let seconds: f64 = seconds.parse().with_context(|| format!("{}: seconds {seconds:?}", at()))?;
        let film = Film::load_exr(&dir.join(image)).with_context(at)?;
        crate::output::compare::check_finite(&film, &dir.join(image))?;
        let c = compare(&film, reference, 0.0).with_context(at)?;
        points.push(ConvergencePoint::of(spp, seconds, &c));
    }
    if points.is_empty() {
        bail!("{}: no renders listed (a header, then spp,seconds,image rows)", csv.display());
    }
    Ok(points)
}

/// Least-squares slope of log(relative MSE) against log(seconds) over the points after the first
/// (whose time is dominated by fixed costs): −1 for an unbiased estimator at constant throughput.
pub fn log_log_slope(points: &[ConvergencePoint]) -> Option<f64> {
    least_squares_log_slope(points.iter().skip(1).map(|p| (p.seconds, p.rel_mse)))
}

/// Least-squares slope of log y against log x over the pairs with both positive (`None` with fewer
/// than two, or all at one x).
pub fn least_squares_log_slope(pairs: impl Iterator<Item = (f64, f64)>) -> Option<f64> {
    let xy: Vec<(f64, f64)> =
        pairs.filter(|&(x, y)| x > 0.0 && y > 0.0).map(|(x, y)| (x.ln(), y.ln())).collect();
    if xy.len() < 2 {
        return None;
    }
    let n = xy.len() as f64;
    let (mx, my) = (xy.iter().map(|p| p.0).sum::<f64>() / n, xy.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Writes the curves as CSV, one row per point
/// (`integrator,spp,seconds,rmse,rel_mse,luminance_ratio,net_mse,net_rel_mse`, the last two empty
/// where the reference has no variance).
pub fn write_csv(path: &Path, curves: &[(&str, &[ConvergencePoint])]) -> Result<()> {
    let mut text = String::from("integrator,spp,seconds,rmse,rel_mse,luminance_ratio,net_mse,net_rel_mse\n");
    let net = |x: Option<f64>| x.map(|x| format!("{x:.8e}")).unwrap_or_default();
    for (integrator, points) in curves {
        for p in points.iter() {
            text += &format!(
                "{integrator},{},{:.6},{:.8e},{:.8e},{:.6},{},{}\n",
                p.spp,
                p.seconds,
                p.rmse,
                p.rel_mse,
                p.luminance_ratio,
                net(p.net_mse),
                net(p.net_rel_mse)
            );
        }
    }
    crate::system::files::write(path, text.as_bytes())
}

/// Plots relative MSE against render seconds on log–log axes (SVG), one series per labelled curve,
/// with a dashed line of slope −1 through the first curve's last point for reference.
pub fn write_plot(path: &Path, curves: &[(String, Vec<ConvergencePoint>)]) -> Result<()> {
    let mut svg = String::new();
    draw_plot(&mut svg, curves).with_context(|| format!("cannot draw {}", path.display()))?;
    crate::system::files::write(path, svg.as_bytes())
}

fn draw_plot(svg: &mut String, curves: &[(String, Vec<ConvergencePoint>)]) -> Result<()> {
    use plotters::prelude::*;
    let all: Vec<&ConvergencePoint> =
        curves.iter().flat_map(|(_, c)| c).filter(|p| p.seconds > 0.0 && p.rel_mse > 0.0).collect();
    if all.is_empty() {
        bail!("nothing to plot");
    }
    let (t0, t1) = all.iter().fold((f64::MAX, 0.0f64), |(a, b), p| (a.min(p.seconds), b.max(p.seconds)));
    let (e0, e1) = all.iter().fold((f64::MAX, 0.0f64), |(a, b), p| (a.min(p.rel_mse), b.max(p.rel_mse)));
    let root = SVGBackend::with_string(svg, (800, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut chart = ChartBuilder::on(&root)
        .caption("relative MSE against render time", ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d((t0 / 1.5..t1 * 1.5).log_scale(), (e0 / 2.0..e1 * 2.0).log_scale())
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    chart
        .configure_mesh()
        .x_desc("render seconds")
        .y_desc("relative MSE")
        .draw()
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let colours = [BLUE, RED, GREEN, MAGENTA, CYAN, BLACK];
    for (k, (label, points)) in curves.iter().enumerate() {
        let colour = colours[k % colours.len()];
        let series: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.seconds > 0.0 && p.rel_mse > 0.0)
            .map(|p| (p.seconds, p.rel_mse))
            .collect();
        chart
            .draw_series(LineSeries::new(series.clone(), colour.stroke_width(2)))
            .map_err(|e| anyhow::anyhow!("{e}"))?
            .label(label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
        chart
            .draw_series(series.iter().map(|&p| Circle::new(p, 3, colour.filled())))
            .map_err(|e| anyhow::anyhow!("{e}"))?;
    }
    if let Some(last) = curves[0].1.iter().rev().find(|p| p.seconds > 0.0 && p.rel_mse > 0.0) {
        let line = [(t0, last.rel_mse * last.seconds / t0), (t1, last.rel_mse * last.seconds / t1)];
        chart
            .draw_series(DashedLineSeries::new(line, 6, 4, BLACK.mix(0.5).stroke_width(1)))
            .map_err(|e| anyhow::anyhow!("{e}"))?
            .label("slope −1")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.5)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    root.present().map_err(|e| anyhow::anyhow!("{e}"))?;
    drop(chart);
    drop(root);
    Ok(())
}
