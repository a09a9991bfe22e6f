//! Mesh files read into `scene::mesh::Mesh`: Wavefront OBJ, PLY (with its named attributes) and
//! Mitsuba's serialized format; `primitives` tessellates Mitsuba's built-in shapes.
mod obj;
mod ply;
mod ply_attributes;
pub mod primitives;
mod serialized;

pub use obj::load_obj;
pub use ply::load_ply;
pub use serialized::load_serialized;
