//! `<transform>`: translate, rotate, scale, matrix and lookat, composed in document order
//! (each later operation is applied after the earlier ones).
use super::xml::{
    attribute, expand_value_to_xyz, parse_numbers, vector_from_node, Loc, Params, Source, XyzError,
};
use crate::scene::look_at;
use anyhow::{bail, Result};
use glam::{Mat4, Vec3};

/// The transform of the `<transform>` element `node` of `src`, `$name` references in its attributes
/// replaced by `params`.
pub fn parse(src: &Source, node: roxmltree::Node, params: &Params, loc: &Loc) -> Result<Mat4> {
    let mut m = Mat4::IDENTITY;
    for op in node.children().filter(|n| n.is_element()) {
        let op_loc = src.loc(op);
        let value = attribute(op, "value", params, &op_loc)?;
        let value = value.as_deref();
        let step = match op.tag_name().name() {
            "translate" => Mat4::from_translation(vector_from_node(op, value, params, &op_loc)?),
            "scale" => Mat4::from_scale(expand_value_to_xyz(op, value, 1.0, params, &op_loc).map_err(
                |e| match e {
                    XyzError::Numbers(e) => e,
                    XyzError::Count(_) => anyhow::anyhow!("{op_loc}: <scale> needs 1 or 3 numbers"),
                    XyzError::NotANumber(_) => anyhow::anyhow!("{op_loc}: <scale> values must be numbers"),
                },
            )?),
            "rotate" => {
                let axis = vector_from_node(op, value, params, &op_loc)?;
                let angle: f32 = match attribute(op, "angle", params, &op_loc)? {
                    Some(a) => {
                        a.trim().parse().map_err(|_| anyhow::anyhow!("{op_loc}: angle must be a number"))?
                    }
                    None => bail!("{op_loc}: <rotate> needs an angle"),
                };
                if axis.length_squared() == 0.0 {
                    bail!("{op_loc}: <rotate> needs a non-zero axis");
                }
                Mat4::from_axis_angle(axis.normalize(), angle.to_radians())
            }
            "matrix" => {
                let n = parse_numbers(value.unwrap_or(""), &op_loc)?;
                if n.len() != 16 {
                    bail!("{op_loc}: <matrix> needs 16 numbers (row-major), got {}", n.len());
                }
                let cols: Vec<f32> = n.iter().map(|&x| x as f32).collect();
                Mat4::from_cols_slice(&cols).transpose()
            }
            "lookat" => {
                let p = |a: &str| -> Result<Vec3> {
                    let s = attribute(op, a, params, &op_loc)?;
                    let s = s.as_deref().unwrap_or(if a == "up" { "0 1 0" } else { "" });
                    vector_from_node(op, Some(s), params, &op_loc)
                };
                match look_at(p("origin")?, p("target")?, p("up")?) {
                    Some(l) => l,
                    None => bail!("{op_loc}: degenerate <lookat> (origin = target, or up parallel to the view direction)"),
                }
            }
            other => bail!("{op_loc}: unknown transform operation <{other}>"),
        };
        m = step * m;
    }
    if !m.is_finite() {
        bail!("{loc}: transform is not finite");
    }
    Ok(m)
}
