//! The pruned kernel (`caustic::backend::prune`: the scene's mask frozen in and the unused paths
//! deleted by spirv-opt) renders the image the specialised kernel renders, on lavapipe, and the
//! cache holds it after the first render. One test in its own binary: it sets `CAUSTIC_PRUNE` and
//! `XDG_CACHE_HOME`, which would change the GPU renders of any test running beside it.
use caustic::backend::BackendChoice;
use caustic_tests::*;

#[test]
fn a_pruned_kernel_renders_the_specialised_image() {
    if std::process::Command::new("spirv-opt").arg("--version").output().is_err() {
        // CI installs spirv-tools (.ci/run); a developer machine without it renders unpruned.
        eprintln!("spirv-opt is not installed: nothing to test here");
        return;
    }
    let cache = std::env::temp_dir().join(format!("caustic-prune-test-{}", std::process::id()));
    std::env::set_var("XDG_CACHE_HOME", &cache);
    let file = "docs/scenes/bsdf_plastic_default.xml";
    let mut scene =
        caustic::load::load_scene(&mitsuba_scene(file), &defines(&[("spp", "4")])).expect("scene loads");
    let (w, h) = (scene.sensor.width, scene.sensor.height);
    scene.sensor.crop = Some(caustic::scene::Crop { x: w / 2 - 16, y: h / 2 - 16, width: 32, height: 32 });
    let buffers = caustic::prepare::buffers::build(&scene).expect("scene builds");

    // The module itself: the constant is gone and so is most of the code.
    let words: Vec<u32> =
        bytemuck::pod_collect_to_vec(include_bytes!("../../host/shaders/caustic-kernel.spv"));
    // (The regenerating path loop: what lavapipe runs unless asked otherwise, `backend::path_loop`.)
    let regenerate = caustic::backend::path_loop::PathLoop::Regenerate.spec_value();
    let pruned = caustic::backend::prune::pruned(&words, buffers.features, regenerate, true)
        .expect("spirv-opt prunes the kernel");
    assert!(pruned.len() < words.len() / 2, "pruned {} words of {}", pruned.len(), words.len());

    std::env::set_var("CAUSTIC_PRUNE", "0");
    let specialised = render_buffers(&buffers, BackendChoice::Gpu, 4, 5);
    std::env::set_var("CAUSTIC_PRUNE", "1");
    let pruned_image = render_buffers(&buffers, BackendChoice::Gpu, 4, 5);
    let entries = std::fs::read_dir(cache.join("caustic").join("pruned")).expect("the cache exists").count();
    std::fs::remove_dir_all(&cache).ok();

    let differ = pixels_differing(&specialised, &pruned_image, 1e-5);
    println!("{differ} of {} pixels differ; {entries} cached module(s)", specialised.rgb.len());
    // As `cross_backend`'s specialization test: the driver compiles two pipelines and may contract
    // floating point differently, so a few paths may diverge; a wrong path would change most pixels.
    assert!(differ <= specialised.rgb.len() / 50, "{differ} pixels differ between pruned and specialised");
    assert_eq!(entries, 1, "one kernel, one mask, one loop: one cache entry");
}
