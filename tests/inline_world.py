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
