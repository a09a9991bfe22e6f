//! Batches: `caustic render` of several scenes, or of one scene's `--vary name=v1,v2,…` variants
//! (every combination), one image each; under mpirun the images are spread over the ranks, each
//! rank rendering its own whole (embarrassingly parallel: nothing is exchanged).
use crate::render::session::RenderJob;
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};

/// `--vary name=v1,v2,…`: the values a scene parameter takes, one image each.
pub fn parse_vary(s: &str) -> Result<(String, Vec<String>), String> {
    match s.split_once('=') {
        Some((name, values)) if !name.is_empty() && !values.is_empty() => {
            let values: Vec<String> = values.split(',').map(str::to_string).collect();
            if values.iter().any(String::is_empty) {
                return Err(format!("'{s}': an empty value in the list"));
            }
            Ok((name.to_string(), values))
        }
        _ => Err(format!("'{s}' is not name=value1,value2,...")),
    }
}

/// One job per scene and combination of the varied values, from `template` (whose scene, defines
/// and output they replace). One job keeps `output` as given (or SCENE's name with `.exr`); several
/// write `SCENE-name=value….exr` into the folder `output` (default: the current one).
pub fn jobs(
    template: &RenderJob,
    scenes: &[PathBuf],
    vary: &[(String, Vec<String>)],
    output: Option<&Path>,
) -> Result<Vec<RenderJob>> {
    let mut combos: Vec<Vec<(String, String)>> = vec![Vec::new()];
    for (name, values) in vary {
        combos = combos
            .into_iter()
            .flat_map(|c| {
                values.iter().map(move |v| {
                    let mut c = c.clone();
                    c.push((name.clone(), v.clone()));
                    c
                })
            })
            .collect();
    }
    let count = scenes.len() * combos.len();
    if count > 1 && template.checkpoint.is_some() {
        bail!("--checkpoint takes one image; this command renders {count}");
    }
    let folder = match output {
        Some(dir) if count > 1 => {
            if dir.extension().is_some() && !dir.is_dir() {
                bail!(
                    "-o {}: with {count} images, -o names a folder (each image is named after its scene \
                     and values)",
                    dir.display()
                );
            }
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create the folder {}", dir.display()))?;
            dir.to_path_buf()
        }
        _ => PathBuf::new(),
    };
    let mut jobs = Vec::with_capacity(count);
    for scene in scenes {
        let stem = scene.file_stem().unwrap_or_default().to_string_lossy().to_string();
        for combo in &combos {
            let mut job = template.clone();
            job.scene = scene.clone();
            job.defines.extend(combo.iter().cloned());
            job.output = if count == 1 {
                output.map_or_else(|| PathBuf::from(&stem).with_extension("exr"), Path::to_path_buf)
            } else {
                let values: String = combo.iter().map(|(n, v)| format!("-{n}={}", file_safe(v))).collect();
                folder.join(format!("{stem}{values}.exr"))
            };
            jobs.push(job);
        }
    }
    let mut names: Vec<&Path> = jobs.iter().map(|j| j.output.as_path()).collect();
    names.sort();
    if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
        bail!(
            "two images of this batch would both be written to {}: give the scenes distinct names",
            w[0].display()
        );
    }
    Ok(jobs)
}

/// A value as part of a file name: path separators replaced.
fn file_safe(v: &str) -> String {
    v.chars().map(|c| if c == '/' || c == '\\' { '_' } else { c }).collect()
}

/// The jobs (indices) that rank `rank` of `size` renders: every `size`-th.
pub fn mine(count: usize, rank: usize, size: usize) -> impl Iterator<Item = usize> {
    (rank..count).step_by(size.max(1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn template() -> RenderJob {
        RenderJob {
            scene: PathBuf::new(),
            defines: vec![("spp".into(), "4".into())],
            backend: crate::backend::BackendChoice::Cpu,
            gpus: Default::default(),
            spp: None,
            seed: 0,
            strict: false,
            output: PathBuf::new(),
            variance: false,
            progress_bar: false,
            checkpoint: None,
            tev: None,
            integrator: None,
            film: Default::default(),
            own_kernel: false,
        }
    }

    #[test]
    fn every_combination_gets_its_own_file() {
        let vary = [parse_vary("res=16,24").unwrap(), parse_vary("max_depth=2,8,-1").unwrap()];
        let dir = std::env::temp_dir().join(format!("caustic-batch-{}", std::process::id()));
        let jobs = jobs(&template(), &[PathBuf::from("a/cbox.xml")], &vary, Some(&dir)).unwrap();
        assert_eq!(jobs.len(), 6);
        assert_eq!(jobs[5].output, dir.join("cbox-res=24-max_depth=-1.exr"));
        assert_eq!(jobs[5].defines[1..], [("res".into(), "24".into()), ("max_depth".into(), "-1".into())]);
        assert_eq!(jobs[0].defines[0], ("spp".to_string(), "4".to_string()));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn one_job_keeps_its_output_and_several_refuse_a_file_or_a_checkpoint() {
        let one = jobs(&template(), &[PathBuf::from("x.xml")], &[], Some(Path::new("y.png"))).unwrap();
        assert_eq!(one[0].output, PathBuf::from("y.png"));
        let two = [PathBuf::from("x.xml"), PathBuf::from("z.xml")];
        let e = jobs(&template(), &two, &[], Some(Path::new("y.png"))).unwrap_err().to_string();
        assert!(e.contains("folder"), "{e}");
        let mut t = template();
        t.checkpoint = Some((PathBuf::from("c.ckpt"), std::time::Duration::ZERO));
        let e = jobs(&t, &two, &[], None).unwrap_err().to_string();
        assert!(e.contains("--checkpoint takes one image"), "{e}");
        let e = jobs(&template(), &[PathBuf::from("a/x.xml"), PathBuf::from("b/x.xml")], &[], None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("x.exr"), "{e}");
        assert!(parse_vary("res=").is_err() && parse_vary("res=1,,2").is_err());
    }

    #[test]
    fn ranks_take_every_nth_job() {
        let all: Vec<Vec<usize>> = (0..2).map(|r| mine(3, r, 2).collect()).collect();
        assert_eq!(all, vec![vec![0, 2], vec![1]]);
    }
}
