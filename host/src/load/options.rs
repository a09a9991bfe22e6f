//! How a scene file is read (`LoadOptions`): what `load_scene_with` and the Mitsuba loader take.

/// How a scene file is read.
#[derive(Clone, Copy, Debug, Default)]
pub struct LoadOptions {
    /// Refuse a Mitsuba scene that would not render as written (an unknown plugin replaced or left
    /// out, a property not read) instead of warning: for pipelines that must not produce a wrong
    /// image silently. The error names the file and line of each such element.
    pub strict: bool,
}
