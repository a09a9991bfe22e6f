//! The `envmap` emitter's `mis_compensation` (Karlík et al. 2019, as Mitsuba reads it): light
//! sampling follows the luminance above the map's mean, BSDF sampling covers the rest, and the image
//! is the one without compensation.
use caustic::backend::BackendChoice;
use caustic::prepare::buffers;
use caustic_kernel::layout::LIGHT_ENVMAP;
use caustic_tests::replicas::*;
use caustic_tests::*;

/// A glossy sphere on a diffuse floor under the shared museum environment.
fn scene(integrator: &str, compensate: bool) -> String {
    let museum = shared_dir().join("scenes/mitsuba/common/textures/museum.exr");
    format!(
        r#"<scene version="3.0.0">
    <integrator type="{integrator}"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, -3, 1.2" target="0, 0, 0.4" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
    <shape type="sphere"><float name="radius" value="0.5"/><point name="center" x="0" y="0" z="0.5"/>
        <bsdf type="roughconductor"><float name="alpha" value="0.25"/></bsdf></shape>
    <emitter type="envmap"><string name="filename" value="{}"/>
        <boolean name="mis_compensation" value="{compensate}"/>
        <transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>
</scene>"#,
        museum.display()
    )
}

/// The envmap's conditional CDFs (`light::infinite`'s layout) and how many of their cells have
/// probability zero.
fn zero_cells(b: &buffers::SceneBuffers) -> usize {
    let env = b.lights.iter().find(|l| l.kind == LIGHT_ENVMAP).expect("an envmap light");
    let t = &b.textures[env.prim as usize];
    let (w, h) = (t.width as usize, t.height as usize);
    let conditional = &b.tables[env.table as usize + (h - 1)..env.table as usize + (h - 1) + (h - 1) * w];
    conditional
        .chunks_exact(w)
        .map(|row| (0..w).filter(|&c| row[c] == if c == 0 { 0.0 } else { row[c - 1] }).count())
        .sum()
}

#[test]
fn compensation_leaves_the_dim_directions_to_bsdf_sampling() {
    let plain = buffers::build(&load_xml(&scene("path", false), "env-plain")).unwrap();
    let compensated = buffers::build(&load_xml(&scene("path", true), "env-comp")).unwrap();
    let (a, b) = (zero_cells(&plain), zero_cells(&compensated));
    let cells = {
        let t = compensated.textures.iter().find(|t| t.width > 1).unwrap();
        t.width as usize * (t.height as usize - 1)
    };
    println!("cells of probability zero: {a} without compensation, {b} with, of {cells}");
    assert!(b > a + cells / 10, "compensation left the distribution as it was ({a} → {b} of {cells})");
    assert!(b < cells, "compensation left nothing to sample");
    // Light tracing draws emission from the tables alone: there compensation is not applied.
    let pt = buffers::build(&load_xml(&scene("ptracer", true), "env-pt")).unwrap();
    assert_eq!(
        zero_cells(&pt),
        zero_cells(&buffers::build(&load_xml(&scene("ptracer", false), "env-pt2")).unwrap())
    );
}

#[test]
fn compensation_renders_the_same_image() {
    for integrator in ["path", "direct"] {
        let plain = render_replicated(&load_xml(&scene(integrator, false), "env-plain-r"), 256, 7);
        let compensated =
            render_scene(&load_xml(&scene(integrator, true), "env-comp-r"), BackendChoice::Cpu, 256, 8);
        let (z, worst) = agreement(&plain, &compensated);
        println!(
            "{integrator}: plain mean {:.5}, compensated mean {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
            plain.mean,
            image_mean(&compensated)
        );
        assert!(plain.mean > 1e-2, "the scene is dark");
        assert!(
            z.abs() < 4.5 && worst < 5.0,
            "{integrator}: compensation changed the image (z {z:+.2}, worst {worst:.2})"
        );
    }
}

/// A 12×7 map with random texels, one bright one and a run of black ones, written as an EXR, and the
/// buffers of a scene lit by it alone (compensated or not).
fn small_map(compensate: bool) -> buffers::SceneBuffers {
    let (w, h) = (12u32, 7u32);
    let mut rng = Xorshift(0x9e37_79b9_7f4a_7c15);
    let mut rgb: Vec<[f32; 3]> = (0..w * h).map(|_| [rng.uniform(), rng.uniform(), rng.uniform()]).collect();
    rgb[2 * w as usize + 5] = [20.0, 15.0, 10.0];
    for texel in &mut rgb[4 * w as usize..4 * w as usize + 4] {
        *texel = [0.0; 3];
    }
    let dir = std::env::temp_dir().join(format!("caustic-envmap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // (One file per call: the tests run in parallel.)
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let map = dir.join(format!("small-{}.exr", CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)));
    caustic::output::film::Film::from_rgb(w, h, rgb).save(&map).unwrap();
    let xml = format!(
        r#"<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
    <shape type="sphere"><float name="radius" value="0.1"/></shape>
    <emitter type="envmap"><string name="filename" value="{}"/>
        <boolean name="mis_compensation" value="{compensate}"/>
        <transform name="to_world"><rotate x="1" y="2" z="0.5" angle="40"/></transform></emitter>
</scene>"#,
        map.display()
    );
    buffers::build(&load_xml(&xml, "env-small")).unwrap()
}

/// The envmap's frame: the world direction of lat-long point (`u`, `v`) (Mitsuba's convention, as
/// `light::infinite` reads it) and the lat-long point of a world direction.
fn world_of(light: &caustic_kernel::layout::Light, u: f64, v: f64) -> glam::Vec3 {
    let (theta, phi) = (v * std::f64::consts::PI, u * 2.0 * std::f64::consts::PI);
    let local = [phi.sin() * theta.sin(), theta.cos(), -phi.cos() * theta.sin()];
    let mut world = glam::Vec3::ZERO;
    for (i, row) in light.to_local.iter().enumerate() {
        world += glam::Vec3::new(row[0], row[1], row[2]) * local[i] as f32;
    }
    world
}

fn uv_of(light: &caustic_kernel::layout::Light, d: glam::Vec3) -> (f64, f64) {
    let local: Vec<f64> =
        light.to_local.iter().map(|r| (glam::Vec3::new(r[0], r[1], r[2]).dot(d)) as f64).collect();
    let u = local[0].atan2(-local[2]) / (2.0 * std::f64::consts::PI);
    (u - u.floor(), local[1].clamp(-1.0, 1.0).acos() / std::f64::consts::PI)
}

/// The density of lat-long point (u, v) (per unit u and v): the solid-angle density times the
/// Jacobian 2π² sin θ.
fn uv_density(b: &buffers::SceneBuffers, light: &caustic_kernel::layout::Light, u: f64, v: f64) -> f64 {
    let pdf = caustic_kernel::light::infinite::pdf(light, &b.view(), world_of(light, u, v)) as f64;
    pdf * 2.0 * std::f64::consts::PI.powi(2) * (v * std::f64::consts::PI).sin()
}

/// χ² test of the envmap's light samples against its density, on a grid of the lat-long square whose
/// bins lie inside single cells (4 × 4 a cell), where the density is bilinear and the midpoint rule
/// integrates it exactly; and every sample's reported density is the one `pdf` gives its direction.
/// Pearson's statistic against its normal approximation (k + 4·√(2k) for k bins).
#[test]
fn light_samples_follow_the_envmap_density() {
    for compensate in [false, true] {
        let b = small_map(compensate);
        let view = b.view();
        let light = *b.lights.iter().find(|l| l.kind == LIGHT_ENVMAP).unwrap();
        let (cols, rows) = (12 * 4, 6 * 4);
        // Bin edges: columns from texel centre 0 (u = 1/24), rows from the top texel row.
        let bin = |u: f64, v: f64| {
            let x = ((u - 1.0 / 24.0).rem_euclid(1.0) * cols as f64) as usize;
            let y = (v * rows as f64) as usize;
            y.min(rows - 1) * cols + x.min(cols - 1)
        };
        let samples = 400_000;
        let mut observed = vec![0.0f64; cols * rows];
        let mut rng = caustic_kernel::rng::Sampler::new(3, 5, compensate as u32);
        for _ in 0..samples {
            let s = caustic_kernel::light::infinite::sample_envmap(
                &light,
                &view,
                glam::Vec3::ZERO,
                rng.next_2d(),
            );
            assert!(s.pdf > 0.0, "a sample without density");
            let pdf = caustic_kernel::light::infinite::pdf(&light, &view, s.wi);
            let (u, v) = uv_of(&light, s.wi);
            // Near a pole θ = acos(y) loses digits (an error of a few f32 ulps in y moves θ by
            // about ulps / sin θ), and the density falls to zero linearly in θ there: its relative
            // error grows as 1 / sin² θ (0.4% measured at sin θ = 0.011, 3.8% at 0.0033).
            let sin_theta = (v * std::f64::consts::PI).sin() as f32;
            let tolerance = 2e-3 + 1e-6 / (sin_theta * sin_theta);
            assert!(
                (pdf - s.pdf).abs() <= tolerance * s.pdf,
                "reported density {} against pdf {pdf} at ({u}, {v})",
                s.pdf
            );
            observed[bin(u, v)] += 1.0;
        }
        let (du, dv) = (1.0 / cols as f64, 1.0 / rows as f64);
        let (mut chi2, mut k, mut mass) = (0.0, 0usize, 0.0);
        for y in 0..rows {
            for x in 0..cols {
                let (u, v) = (1.0 / 24.0 + (x as f64 + 0.5) * du, (y as f64 + 0.5) * dv);
                let p = uv_density(&b, &light, u.rem_euclid(1.0), v) * du * dv;
                mass += p;
                let (o, e) = (observed[y * cols + x], p * samples as f64);
                if e > 0.0 {
                    chi2 += (o - e).powi(2) / e;
                    k += 1;
                } else {
                    assert_eq!(o, 0.0, "samples where the density is zero");
                }
            }
        }
        let limit = k as f64 + 4.0 * (2.0 * k as f64).sqrt();
        println!(
            "compensate {compensate}: χ² {chi2:.0} over {k} bins (limit {limit:.0}), density mass {mass:.5}"
        );
        assert!((mass - 1.0).abs() < 1e-3, "the density integrates to {mass}");
        assert!(chi2 < limit, "samples do not follow the density: χ² {chi2:.0} > {limit:.0}");
    }
}

/// The density follows the map between texels as its radiance does: per unit of the lat-long square
/// it is proportional to luminance · sin θ at every texel, not to the mean of the texel's cells (what
/// sampling a cell uniformly gave).
#[test]
fn the_envmap_density_is_the_texels_bilinear_interpolant() {
    let b = small_map(false);
    let light = *b.lights.iter().find(|l| l.kind == LIGHT_ENVMAP).unwrap();
    let t = &b.textures[light.prim as usize];
    let mut ratios = Vec::new();
    for y in 1..t.height - 1 {
        for x in 0..t.width {
            let texel = caustic_kernel::texture::texel(t, &b.tables, x, y);
            let (u, v) = ((x as f64 + 0.5) / t.width as f64, y as f64 / (t.height - 1) as f64);
            let weight = caustic_kernel::spectrum::luminance(texel) as f64 * (v * std::f64::consts::PI).sin();
            let density = uv_density(&b, &light, u, v);
            if weight > 0.0 {
                ratios.push(density / weight);
            } else {
                assert!(density < 1e-6, "density {density} at a black texel ({x}, {y})");
            }
        }
    }
    let (lo, hi) = ratios.iter().fold((f64::MAX, 0.0f64), |(lo, hi), r| (lo.min(*r), hi.max(*r)));
    println!("density / (luminance · sin θ) at {} texels: {lo:.5} to {hi:.5}", ratios.len());
    assert!(hi / lo < 1.001, "the density does not follow the texels ({lo} to {hi})");
}
