//! The AOVs a scene asks for (`scene::aov::AovSpec`) rendered (`pass`) and developed into the
//! film's extra channels, and the multi-channel EXR files that hold them (`exr`).
pub mod exr;
pub mod pass;

use crate::output::film::{AovChannel, Film};
use crate::scene::aov::AovSpec;

impl AovSpec {
    /// Puts the rendered AOVs (`computed`: `computed_channels`' order, per pixel; their variances of
    /// the mean in `variance`) into `film`: the depth integrator's replace the image; otherwise
    /// they become its extra channels, after the nested image's copy, and without a nested
    /// integrator the image is black.
    pub fn develop(&self, film: &mut Film, computed: Vec<Vec<f32>>, variance: Vec<Vec<f64>>) {
        if self.depth_image {
            film.rgb = computed[0].iter().map(|&d| [d; 3]).collect();
            film.variance = Some(variance[0].iter().map(|&v| [v; 3]).collect());
            return;
        }
        let mut channels = Vec::new();
        match &self.nested {
            Some(n) => {
                for (c, suffix) in ["R", "G", "B"].iter().enumerate() {
                    channels.push(AovChannel {
                        name: format!("{n}.{suffix}"),
                        values: film.rgb.iter().map(|p| p[c]).collect(),
                        variance: film.variance.as_ref().map(|v| v.iter().map(|p| p[c]).collect()),
                    });
                }
            }
            None => {
                film.rgb.iter_mut().for_each(|p| *p = [0.0; 3]);
                if let Some(v) = film.variance.as_mut() {
                    v.iter_mut().for_each(|p| *p = [0.0; 3]);
                }
            }
        }
        let computed = self.computed_channels().into_iter().zip(computed).zip(variance);
        for ((name, values), variance) in computed {
            channels.push(AovChannel { name, values, variance: Some(variance) });
        }
        film.aovs = channels;
    }
}

/// Renders the scene's AOVs, if it has any, over samples `[0, spp)` with `seed` (the image's) and
/// puts them into `film` (`AovSpec::develop`). A scene without AOVs costs nothing here.
pub fn add_to(film: &mut Film, buffers: &crate::prepare::buffers::SceneBuffers, spp: u32, seed: u32) {
    if let Some(spec) = &buffers.aovs {
        if spec.computed_channels().is_empty() {
            // An `aov` with neither AOVs nor a nested integrator: a black image, nothing to trace.
            spec.develop(film, Vec::new(), Vec::new());
            return;
        }
        let (values, variance) = pass::render(buffers, spec, spp, seed);
        spec.develop(film, values, variance);
    }
}
