//! The sensor as the kernel sees it: its camera, and how far the splatting film spreads a sample.
use crate::scene::{Projection, Scene};
use caustic_kernel::camera::{
    Camera, CAMERA_IRRADIANCE_METER, CAMERA_ORTHOGRAPHIC, CAMERA_PERSPECTIVE, CAMERA_THIN_LENS,
};
use caustic_kernel::layout::*;

/// The kernel's camera for a sensor.
pub fn camera(scene: &Scene) -> Camera {
    let s = &scene.sensor;
    let tan_half_x = (s.fov_x.to_radians() * 0.5).tan();
    let mut camera = Camera {
        origin: s.to_world.w_axis.truncate().to_array(),
        near_clip: s.near_clip,
        axis_x: s.to_world.x_axis.truncate().to_array(),
        tan_half_x,
        axis_y: s.to_world.y_axis.truncate().to_array(),
        tan_half_y: tan_half_x * s.height as f32 / s.width as f32,
        axis_z: s.to_world.z_axis.truncate().to_array(),
        far_clip: s.far_clip,
        kind: CAMERA_PERSPECTIVE,
        ..Default::default()
    };
    match s.projection {
        Projection::Perspective => camera.principal_offset = s.principal_point_offset,
        Projection::ThinLens { aperture_radius, focus_distance } => {
            camera.kind = CAMERA_THIN_LENS;
            camera.aperture_radius = aperture_radius;
            camera.focus_distance = focus_distance;
        }
        Projection::Orthographic { half_width, half_height } => {
            camera.kind = CAMERA_ORTHOGRAPHIC;
            camera.tan_half_x = half_width;
            camera.tan_half_y = half_height;
        }
        Projection::RadianceMeter => {
            camera.tan_half_x = 0.0;
            camera.tan_half_y = 0.0;
        }
        // Its primitives' table is placed by `build`.
        Projection::IrradianceMeter { .. } => camera.kind = CAMERA_IRRADIANCE_METER,
    }
    camera
}

/// How far the splatting film spreads a camera sample (`FrameParams::film_reach`), or 0 for filter
/// importance sampling: asked for (`--film fis`), for `ptracer` (no camera samples), for the
/// irradiance and radiance meters (one value, no neighbours), where splatting is the same (a box of
/// radius ½), and for a filter wider than `film_splat::MAX_REACH` pixels, with a warning. The camera
/// halves of `ibpt`, `bdpt` and `vcm` splat into the pixels their filter reaches as `path`'s samples
/// do (their MIS against light tracing then sees camera samples of density one: `film::camera_density`).
pub(super) fn film_reach(sensor: &crate::scene::Sensor, integrator: u32) -> u32 {
    use caustic_kernel::film_splat::{reach_for_radius, MAX_REACH};
    let meter = matches!(sensor.projection, Projection::RadianceMeter | Projection::IrradianceMeter { .. });
    if sensor.film != crate::scene::FilmMode::Splat || meter || integrator == INTEGRATOR_PTRACER {
        return 0;
    }
    let reach = reach_for_radius(sensor.filter.radius());
    if reach > MAX_REACH {
        eprintln!(
            "warning: the reconstruction filter's radius {} reaches {reach} pixels, past the splatting \
             film's {MAX_REACH}: its samples are drawn from the filter instead (as --film fis)",
            sensor.filter.radius()
        );
        return 0;
    }
    reach
}
