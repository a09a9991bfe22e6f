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

/// `$name` in a reference's `id` picks the object by parameter, as in Mitsuba 3.9.1 (checked there:
/// `mi.load_file(..., material="blue")` renders this sphere blue); a duplicate id is found after
/// substitution, and an undefined parameter in an id names its line.
#[test]
fn references_take_parameters_too() {
    let scene = |extra: &str| {
        format!(
            r#"<scene version="3.0.0">
    <default name="material" value="red"/>
    <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>
    <bsdf type="diffuse" id="blue"><rgb name="reflectance" value="0.1, 0.1, 0.8"/></bsdf>
    {extra}
    <shape type="sphere"><ref id="$material"/></shape>
</scene>"#
        )
    };
    let red = |s: &caustic::scene::Scene| s.materials[s.shapes[0].material as usize].reflectance[0];
    assert_eq!(red(&load_xml(&scene(""), "ref-default")), 0.8, "the default names the red BSDF");
    let blue = try_load_xml(&scene(""), "ref-d", &[("material", "blue")]).expect("loads");
    assert_eq!(red(&blue), 0.1, "-D material=blue names the blue BSDF");
    let twice = try_load_xml(&scene(r#"<bsdf type="diffuse" id="$material"/>"#), "ref-twice", &[]);
    let e = format!("{:#}", twice.expect_err("red is given twice"));
    assert!(e.contains("duplicate id \"red\"") && e.contains(".xml:5"), "{e}");
    let undefined = try_load_xml(&scene(r#"<bsdf type="diffuse" id="$colour"/>"#), "ref-undefined", &[]);
    let e = format!("{:#}", undefined.expect_err("$colour is undefined"));
    assert!(e.contains("$colour") && e.contains(".xml:5"), "{e}");
}
