"""Missing meshes are replaced, never a failure."""

from __future__ import annotations

from hexaleg.robot.meshes import resolve_mesh, with_available_meshes

INERTIA = ('<inertial><origin xyz="0 0 0.1"/><mass value="2.0"/><inertia ixx="{0}" iyy="{1}" '
           'izz="{2}" ixy="0" ixz="0" iyz="0"/></inertial>')


def test_missing_visual_takes_the_collision_shape(spider):
    assert any("visual mesh package://spider_description/meshes/body.stl not found; drawn "
               "with its collision box" in n for n in spider.notes)
    shapes = [type(o.geometry).__name__ for o in spider.visual_model.geometryObjects
              if o.parentJoint == 1]
    assert shapes == ["Box"]


def test_missing_collision_mesh_becomes_the_inertia_box(tmp_path):
    """A uniform 0.1 × 0.2 × 0.3 m box of 2 kg has I = m (b² + c²)/12 …: its box comes back."""
    m, a, b, c = 2.0, 0.1, 0.2, 0.3
    moments = (m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12)
    urdf = ("<robot name='r'><link name='base'>" + INERTIA.format(*moments)
            + "<collision><geometry><mesh filename='missing.stl'/></geometry></collision>"
            + "</link></robot>")
    text, notes = with_available_meshes(urdf, tmp_path, [])
    assert notes == ["link base: collision mesh missing.stl not found; replaced by its inertia "
                     "box 0.1 × 0.2 × 0.3 m"]
    assert 'size="0.1 0.2 0.3"' in text and 'xyz="0 0 0.1"' in text


def test_found_meshes_become_absolute(tmp_path):
    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    mesh = tmp_path / "pkg" / "meshes" / "m.stl"
    mesh.write_text("solid m\nendsolid m\n")
    assert resolve_mesh("package://pkg/meshes/m.stl", tmp_path / "urdf", [tmp_path]) == mesh
    assert resolve_mesh("meshes/m.stl", tmp_path / "pkg", []) == mesh
    assert resolve_mesh("package://pkg/meshes/none.stl", tmp_path, [tmp_path]) is None


def test_a_link_without_inertia_loses_its_missing_mesh(tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text("<robot name='r'><link name='base'>" + INERTIA.format(1e-3, 1e-3, 1e-3)
                    + "</link><link name='tip'><visual><geometry><mesh filename='x.dae'/>"
                    "</geometry></visual></link><joint name='j' type='revolute'><parent "
                    "link='base'/><child link='tip'/><axis xyz='0 0 1'/><limit lower='-1' "
                    "upper='1' effort='1' velocity='1'/></joint></robot>")
    _, notes = with_available_meshes(urdf.read_text(), tmp_path, [])
    assert notes == ["link tip: visual mesh x.dae not found and no inertia to size a box; "
                     "dropped"]
