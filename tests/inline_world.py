"""Small worlds written inline as text, for tests."""

from ev3sim2d.world.maze_file import parse_maze


def arena(
    width=20, height=20, cell_cm=12, start="x_cm: 60\n  y_cm: 120\n  heading_deg: 0", inner=None, extra=""
):
    """A walled arena of width × height cells; `inner` replaces the rows inside the border."""
    rows = ["#" * width]
    inner = inner or ["#" + "." * (width - 2) + "#"] * (height - 2)
    rows += inner
    rows.append("#" * width)
    grid = "\n".join("  " + r for r in rows)
    text = f"title: test\ncell_cm: {cell_cm}\ngrid: |\n{grid}\nstart:\n  {start}\n{extra}"
    return parse_maze(text, "<test arena>")


def two_wheel_robot(name: str, *sensors: str) -> str:
    """A robot file's text: the driving base's wheels and body, and these sensor entries (YAML flow
    mappings, e.g. "{port: 1, kind: touch, angle_deg: 0, radius_cm: 9, facing: forward}")."""
    lines = "".join(f"  - {sensor}\n" for sensor in sensors)
    return (
        f"name: {name}\nwheel_diameter_mm: 56\naxle_track_mm: 120\n"
        "body: {front_cm: 9, back_cm: 7, width_cm: 15}\n"
        "motors:\n  - {port: B, kind: large, wheel: left}\n  - {port: C, kind: large, wheel: right}\n"
        f"sensors:\n{lines}"
    )


def robot_file(folder, *sensors: str, name: str = "robot.yaml"):
    """two_wheel_robot("test", *sensors) written as `name` in folder: its path."""
    path = folder / name
    path.write_text(two_wheel_robot("test", *sensors))
    return path
