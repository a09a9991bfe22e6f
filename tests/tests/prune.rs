//! The pruned kernel (`caustic::backend::prune`: the scene's mask frozen in and the blocks it
//! disables deleted) renders the image the specialised kernel renders, on lavapipe, and is valid
//! SPIR-V for Vulkan. One test in its own binary: it sets `CAUSTIC_PRUNE`, which would change the
//! GPU renders of any test running beside it.
use caustic::backend::BackendChoice;
use caustic_tests::*;

#[test]
fn a_pruned_kernel_renders_the_specialised_image() {
    let file = "docs/scenes/bsdf_plastic_default.xml";
    let mut scene =
        caustic::load::load_scene(&mitsuba_scene(file), &defines(&[("spp", "4")])).expect("scene loads");
    let (w, h) = (scene.sensor.width, scene.sensor.height);
    scene.sensor.crop = Some(caustic::scene::Crop { x: w / 2 - 16, y: h / 2 - 16, width: 32, height: 32 });
    let buffers = caustic::prepare::buffers::build(&scene).expect("scene builds");

    // The module itself: the constants are gone and so is most of the code.
    let words: Vec<u32> =
        bytemuck::pod_collect_to_vec(include_bytes!("../../host/shaders/caustic-kernel.spv"));
    // (The regenerating path loop: what lavapipe runs unless asked otherwise, `backend::path_loop`.)
    let regenerate = caustic::backend::path_loop::PathLoop::Regenerate.spec_value();
    let pruned =
        caustic::backend::prune::pruned(&words, buffers.features, regenerate).expect("the kernel prunes");
    assert!(pruned.len() < words.len() / 10, "pruned {} words of {}", pruned.len(), words.len());
    // Vulkan's own validator, where it is installed (CI installs it: .ci/run), on this module and on
    // every single feature's, none and all, under both loops; naga, which wgpu reads modules with,
    // checks the same in `prune`'s unit tests.
    // One validator a core at once (the whole kernel's, mask `u32::MAX`, takes it a minute here).
    let file = std::env::temp_dir().join(format!("caustic-pruned-{}.spv", std::process::id()));
    let masks = (0..32).map(|bit| 1u32 << bit).chain([0, u32::MAX]);
    let modules: Vec<(u32, u32)> =
        masks.flat_map(|mask| [(mask, 0), (mask, 1)]).chain([(buffers.features, regenerate)]).collect();
    let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
    'batches: for batch in modules.chunks(cores) {
        let mut runs = Vec::new();
        for (k, &(mask, path_loop)) in batch.iter().enumerate() {
            let module = caustic::backend::prune::pruned(&words, mask, path_loop).expect("the kernel prunes");
            let path = file.with_extension(format!("{k}.spv"));
            std::fs::write(&path, bytemuck::cast_slice(&module)).unwrap();
            let child = std::process::Command::new("spirv-val")
                .arg("--target-env")
                .arg("vulkan1.2")
                .arg(&path)
                .stdout(std::process::Stdio::piped())
                .stderr(std::process::Stdio::piped())
                .spawn();
            match child {
                Ok(child) => runs.push((mask, path_loop, path, child)),
                Err(_) => {
                    std::fs::remove_file(&path).ok();
                    eprintln!("spirv-val is not installed: the modules are not checked by it");
                    break 'batches;
                }
            }
        }
        for (mask, path_loop, path, child) in runs {
            let out = child.wait_with_output().expect("spirv-val ran");
            std::fs::remove_file(&path).ok();
            assert!(
                out.status.success(),
                "mask {mask:#x}, loop {path_loop}: spirv-val: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }

    std::env::set_var("CAUSTIC_PRUNE", "0");
    let specialised = render_buffers(&buffers, BackendChoice::Gpu, 4, 5);
    std::env::set_var("CAUSTIC_PRUNE", "1");
    let pruned_image = render_buffers(&buffers, BackendChoice::Gpu, 4, 5);

    // The negative control: the kernel pruned to the scene's mask less its emitters' bits (12-19),
    // run as a frozen module (`CAUSTIC_KERNEL_SPV`), renders another image.
    let wrong = caustic::backend::prune::pruned(&words, buffers.features & !0x000f_f000, regenerate).unwrap();
    std::fs::write(&file, bytemuck::cast_slice(&wrong)).unwrap();
    std::env::set_var("CAUSTIC_KERNEL_SPV", &file);
    let without_emitters = render_buffers(&buffers, BackendChoice::Gpu, 4, 5);
    std::env::remove_var("CAUSTIC_KERNEL_SPV");
    std::fs::remove_file(&file).ok();
    let wrongly = pixels_differing(&specialised, &without_emitters, 1e-5);
    assert!(wrongly > specialised.rgb.len() / 2, "a wrong mask changed only {wrongly} pixels");

    let differ = pixels_differing(&specialised, &pruned_image, 1e-5);
    println!("{differ} of {} pixels differ ({wrongly} with the wrong mask)", specialised.rgb.len());
    // As `cross_backend`'s specialization test: the driver compiles two pipelines and may contract
    // floating point differently, so a few paths may diverge; a wrong path would change most pixels.
    assert!(differ <= specialised.rgb.len() / 50, "{differ} pixels differ between pruned and specialised");
}
