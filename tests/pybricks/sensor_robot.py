"""What the sensor tests share: a robot file of the EV3 driving base with the sensors a test names."""

from __future__ import annotations


def robot_file(tmp_path, *sensors, name="robot.yaml"):
    """A driving base (motors B left, C right) with these sensor entries (YAML flow mappings)."""
    path = tmp_path / name
    lines = "".join(f"  - {sensor}\n" for sensor in sensors)
    path.write_text(
        "name: test\nwheel_diameter_mm: 56\naxle_track_mm: 120\n"
        "body: {front_cm: 9, back_cm: 7, width_cm: 15}\n"
        "motors:\n  - {port: B, kind: large, wheel: left}\n  - {port: C, kind: large, wheel: right}\n"
        f"sensors:\n{lines}"
    )
    return path
