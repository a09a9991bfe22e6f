//! Scene parameters (`<default>`, `-D name=value`): as in Mitsuba, `$name` may stand in any
//! attribute, not only in `value`: a point's `x`, `y`, `z`, a rotation's `angle`, a look-at's
//! `origin`, a transform's `value`. A scene written with parameters loads as the same scene written
//! out.
use caustic_tests::*;

/// The shapes' geometry, for comparing scenes read from different files.
fn geometry(scene: &caustic::scene::Scene) -> String {
    format!("{:?}", scene.shapes.iter().map(|s| &s.geometry).collect::<Vec<_>>())
}

fn scene(center: &str, angle: &str, origin: &str, shift: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <default name="cx" value="0.25"/><default name="turn" value="30"/><default name="eye" value="0, -4, 1"/>
    <default name="shift" value="0.5 0 0"/>
    <sensor type="perspective"><transform name="to_world"><lookat origin="{origin}" target="0, 0, 0"/></transform></sensor>
    <shape type="sphere"><point name="center" {center}/><float name="radius" value="0.5"/></shape>
    <shape type="rectangle"><transform name="to_world"><rotate z="1" angle="{angle}"/><translate value="{shift}"/></transform></shape>
</scene>"#
    )
}

#[test]
fn parameters_stand_in_any_attribute() {
    let with = load_xml(&scene(r#"x="$cx" y="0" z="0.5""#, "$turn", "$eye", "$shift"), "params");
    let written =
        load_xml(&scene(r#"x="0.25" y="0" z="0.5""#, "30", "0, -4, 1", "0.5 0 0"), "params-written");
    assert_eq!(geometry(&with), geometry(&written), "shapes differ");
    assert_eq!(format!("{:?}", with.sensor), format!("{:?}", written.sensor), "sensors differ");
    // -D overrides a default in those attributes too.
    let moved = try_load_xml(
        &scene(r#"x="$cx" y="0" z="0.5""#, "$turn", "$eye", "$shift"),
        "params-d",
        &[("cx", "0.75")],
    )
    .expect("loads");
    let undefined =
        try_load_xml(&scene(r#"x="$cx" y="0" z="0.5""#, "$spin", "$eye", "$shift"), "params-undefined", &[]);
    let expected = load_xml(&scene(r#"x="0.75" y="0" z="0.5""#, "30", "0, -4, 1", "0.5 0 0"), "params-moved");
    assert_eq!(geometry(&moved), geometry(&expected), "-D did not reach the point");
    let e = format!("{:#}", undefined.expect_err("$spin is undefined"));
    assert!(e.contains("$spin") && e.contains(".xml:6"), "{e}");
}
