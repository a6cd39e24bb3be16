"""The Python API of the installed package, as a notebook or script user calls it from a folder of their
own: `simulate` on a shipped world and on a world built with `World.from_text`, saved and read back; the
result's timelines, table, picture and notebook view; a chart with the `plot` extra, and the install
command when matplotlib is missing."""

import json
import textwrap

SCRIPT_PRELUDE = "import json, sys\nfrom ev3sim2d import World, load_maze, simulate\n"


def run_script(installed, folder, script: str, *python_options: str):
    """`python script.py` in the user's folder, with the installed venv's python; its last line is JSON."""
    (folder / "script.py").write_text(SCRIPT_PRELUDE + textwrap.dedent(script))
    done = installed.run("python", *python_options, "script.py", cwd=folder, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.splitlines()[-1])


def test_simulate_runs_a_shipped_example_in_a_shipped_world_by_name(installed, user_folder):
    installed.run("ev3sim2d", "examples", cwd=user_folder)
    facts = run_script(
        installed,
        user_folder,
        """
        result = simulate("examples/line_follower.py", world="line", time_s=3)
        table = result.table(every_s=1.0)
        png = result.png("end.png")
        page = result._repr_html_()
        print(json.dumps({
            "status": result.status, "rows": len(result.times), "poses": list(result.poses.shape),
            "sensors": sorted(result.sensors), "motors": sorted(result.motors),
            "table_rows": len(table), "png": png[:4].decode("latin-1"),
            "video": "data:video/mp4;base64," in page, "summary": result.fingerprint in page,
        }))
        """,
    )
    assert facts["status"] == "time_limit"  # a line follower never ends by itself
    assert facts["poses"] == [facts["rows"], 3] and facts["rows"] > 10
    assert "in3" in facts["sensors"] and "outB.speed" in facts["motors"]
    assert facts["table_rows"] == 4  # 0, 1, 2, 3 s
    assert facts["png"] == "\x89PNG" and (user_folder / "end.png").read_bytes().startswith(b"\x89PNG")
    assert facts["video"] and facts["summary"]  # in Jupyter: an inline video and a summary


def test_a_world_built_in_python_is_saved_read_back_and_run_from_the_command_line(installed, user_folder):
    facts = run_script(
        installed,
        user_folder,
        """
        world = World.from_text(
            '''
            ##############
            #............#
            #............#
            #......k.....#
            #............#
            ##############
            ''',
            cell_cm=10, starts=[(2, 2, 0)], title="Across a line",
        )
        world.set_cell(11, 2, "g")
        world.add_region("end", cells=[(11, 2)])
        world.save("across.yaml")
        again = load_maze("across.yaml")
        drive = '''
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 2)
        print("there")
        '''
        built, read_back = simulate(drive, world=world, time_s=5), simulate(drive, world="across.yaml", time_s=5)
        x, y, _ = read_back.poses[-1]
        print(json.dumps({
            "equal": again.grid == world.grid and again.starts == world.starts,
            "regions": sorted(again.regions), "same_run": built.fingerprint == read_back.fingerprint,
            "printed": [line.text for line in read_back.output], "moved_cm": float(x - read_back.poses[0][0]),
        }))
        """,
    )
    assert facts["equal"] and facts["regions"] == ["end"]
    assert facts["same_run"]  # a world built in Python runs as its saved file does
    assert facts["printed"] == ["there"] and facts["moved_cm"] > 20
    (user_folder / "drive.py").write_text("print('hello')\n")
    done = installed.run(
        "ev3sim2d", "run", "drive.py", "--maze", "across.yaml", "--time", "1", "--png", "a.png",
        cwd=user_folder,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "hello" in done.stdout and (user_folder / "a.png").read_bytes().startswith(b"\x89PNG")


def test_a_chart_with_the_plot_extra_and_the_install_command_without_it(installed, user_folder):
    chart = """
    result = simulate("print(1)", world="line", time_s=1)
    try:
        figure = result.plot(["x_cm", "outB.speed"], path="chart.png")
        print(json.dumps({"panels": len(figure.axes)}))
    except ImportError as error:
        print(json.dumps({"error": str(error)}))
    """
    assert run_script(installed, user_folder, chart) == {"panels": 2}
    assert (user_folder / "chart.png").read_bytes().startswith(b"\x89PNG")
    # a user who installed the wheel without [plot]: matplotlib hidden, as if never installed
    without = run_script(installed, user_folder, chart, "-c", HIDE_MATPLOTLIB)
    assert without == {
        "error": "plotting needs matplotlib: pip install 'ev3sim2d[plot]' (or pip install matplotlib)"
    }


HIDE_MATPLOTLIB = (
    "import runpy, sys; sys.modules['matplotlib'] = None; sys.argv = ['script.py']; "
    "runpy.run_path('script.py', run_name='__main__')"
)
