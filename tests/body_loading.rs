//! URDF loading: any tree loads; malformed files give errors that name the element.

use posture_opt::body::{BodyError, BodyModel, JointKind};

fn load(body: &str) -> Result<BodyModel, BodyError> {
    BodyModel::from_urdf_str(
        &format!("<?xml version=\"1.0\"?><robot name=\"r\">{body}</robot>"),
        "test.urdf",
    )
}

fn err(body: &str) -> String {
    load(body).unwrap_err().to_string()
}

const L: &str = "<link name=\"a\"/><link name=\"b\"/>";

#[test]
fn all_joint_kinds_load_and_massless_links_are_massless() {
    let m = load(
        "<link name=\"a\"/><link name=\"b\"/><link name=\"c\"><inertial><mass value=\"2\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link><link name=\"d\"/><link name=\"e\"/>
         <joint name=\"j1\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"5\" velocity=\"1\"/></joint>
         <joint name=\"j2\" type=\"continuous\"><parent link=\"b\"/><child link=\"c\"/><axis xyz=\"0 1 0\"/></joint>
         <joint name=\"j3\" type=\"prismatic\"><parent link=\"c\"/><child link=\"d\"/><axis xyz=\"1 0 0\"/><limit lower=\"0\" upper=\"0.5\" effort=\"5\" velocity=\"1\"/></joint>
         <joint name=\"j4\" type=\"fixed\"><parent link=\"a\"/><child link=\"e\"/></joint>
         <transmission name=\"t\"><joint name=\"ghost\"/></transmission>",
    )
    .unwrap();
    assert_eq!(m.nq(), 3);
    assert_eq!(m.joints.len(), 4, "only top-level <joint> elements count");
    assert_eq!(m.links[m.frame_link("b").unwrap()].mass_kg, 0.0);
    assert_eq!(m.total_mass_kg(), 2.0);
    assert_eq!(
        m.joints
            .iter()
            .filter(|j| j.kind == JointKind::Fixed)
            .count(),
        1
    );
    // any link or joint name is a frame; a joint names its child link
    assert_eq!(m.frame_link("j3").unwrap(), m.frame_link("d").unwrap());
    assert!(m.frame_link("nope").is_err());
}

#[test]
fn malformed_files_name_the_element() {
    let e = err(&format!("{L}<joint name=\"j\" type=\"revolute\"><parent link=\"x\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/></joint>"));
    assert!(
        e.contains("test.urdf")
            && e.contains("joint 'j'")
            && e.contains("parent link 'x' does not exist"),
        "{e}"
    );
    let e = err(&format!(
        "{L}<joint name=\"j\" type=\"floating\"><parent link=\"a\"/><child link=\"b\"/></joint>"
    ));
    assert!(
        e.contains("joint 'j'") && e.contains("unsupported type 'floating'"),
        "{e}"
    );
    let e = err(&format!("{L}<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 0\"/></joint>"));
    assert!(
        e.contains("joint 'j' <axis>") && e.contains("non-zero"),
        "{e}"
    );
    let e = err("<link name=\"a\"><inertial><mass value=\"-1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>");
    assert!(e.contains("link 'a'") && e.contains("mass"), "{e}");
    let e = err("<link name=\"a\"><inertial><mass value=\"nan\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>");
    assert!(e.contains("link 'a'") && e.contains("mass"), "{e}");
    // a cycle: a -> b -> a, plus root r
    let e = err("<link name=\"r\"/><link name=\"a\"/><link name=\"b\"/>
        <joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>
        <joint name=\"ba\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint>");
    assert!(e.contains("cycle"), "{e}");
    let e = err("<link name=\"a\"/><link name=\"b\"/>
        <joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>
        <joint name=\"ba\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint>");
    assert!(e.contains("cycle"), "{e}");
    let e = err(&format!("{L}<link name=\"c\"/><joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>"));
    assert!(e.contains("one root") && e.contains('c'), "{e}");
    let e = err(&format!("{L}<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint><joint name=\"k\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>"));
    assert!(
        e.contains("joint 'k'") && e.contains("already has parent joint 'j'"),
        "{e}"
    );
    let e = err("<link name=\"a\"/><link name=\"a\"/>");
    assert!(e.contains("link 'a'") && e.contains("twice"), "{e}");
    let e = BodyModel::from_urdf_str("<robot><link name=", "broken.urdf")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("broken.urdf: not a valid URDF"), "{e}");
    let e = BodyModel::from_urdf_file("/nonexistent/x.urdf")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("/nonexistent/x.urdf") && e.contains("cannot read"),
        "{e}"
    );
}
