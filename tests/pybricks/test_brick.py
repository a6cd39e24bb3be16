"""The EV3 brick in Pybricks 2.0 (pybricks.hubs.EV3Brick) and EV3 MicroPython 1.0's pybricks.ev3brick, in
simulated runs: what a program draws is on the LCD frames, what it plays is in the sound events and lasts
as long as on a brick, the light is in the LED events, the buttons follow the scripted presses.

Firmware: pybricks-micropython v2.0.0 (bricks/ev3dev/pb_type_ev3dev_image.c, pb_type_ev3dev_speaker.c,
extmod/modhubs.c, modbuttons.c, modbattery.c, modbuiltins.c, lib/pbio/drv/ev3dev_stretch/light.c,
bricks/ev3dev/modules/pybricks/{ev3brick,speaker,display}.py).
"""

import numpy as np

from ev3sim2d.world.button_press import parse_press

W, H = 178, 128


def printed(result) -> list[str]:
    return [line.text for line in result.trace.output if line.stream == "stdout"]


def last_frame(result) -> np.ndarray:
    return np.frombuffer(result.trace.lcd_frames[-1], dtype=np.uint8).reshape(H, W)


def frame_at(result, index: int) -> np.ndarray:
    return np.frombuffer(result.trace.lcd_frames[index], dtype=np.uint8).reshape(H, W)


def events(result, kind: str) -> list[list]:
    return [e for e in result.trace.events if e[2] == kind]


def sounds(result, kind: str) -> list[dict]:
    return [e[3] for e in events(result, "sound") if e[3]["kind"] == kind]


def check_ok(result):
    assert result.status == "finished", (result.reason, result.error)
    return result


# ------------------------------------------------------------------------------------------------ screen
def test_screen_draws_at_once_on_the_lcd(run):
    """pb_type_ev3dev_image.c: Image('_screen_') draws into GRX's screen context, the LCD itself, so each
    draw_* shows without an update(); the screen is cleared to white at its first drawing (clear_once),
    draw_box(..., fill=True) fills x1..x2, y1..y2 inclusive; width and height are the LCD's, 178 x 128."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            from pybricks.tools import wait
            ev3 = EV3Brick()
            print(ev3.screen.width, ev3.screen.height)
            ev3.screen.draw_box(10, 20, 59, 39, fill=True)
            wait(200)
            ev3.screen.draw_circle(120, 64, 20, fill=True)
            wait(200)
            ev3.screen.draw_line(0, 127, 177, 127, width=1)
            ev3.screen.draw_pixel(170, 5)
            """
        )
    )
    assert printed(result) == ["178 128"]
    lcd = events(result, "lcd")
    assert len(lcd) >= 3 and lcd[0][0] < 0.1  # (drawn at once, not when the program ends)
    first = frame_at(result, lcd[0][3]["frame"])
    assert (first[20:40, 10:60] == 0).all()
    assert (first[:20] == 255).all() and (first[40:] == 255).all() and (first[:, 60:] == 255).all()
    end = last_frame(result)
    assert end[64, 120] == 0 and end[64, 100] == 0 and end[64, 141] == 255
    assert (end[127] == 0).all() and end[5, 170] == 0 and end[5, 169] == 255
    assert set(np.unique(end)) <= {0, 255}  # (a monochrome LCD)


def test_screen_text_colours_and_clear(run):
    """pb_type_ev3dev_image.c draw_text: text in text_color (BLACK by default) on background_color (None:
    none); map_color turns a Color into GRX's colour, which the EV3's one-bit screen shows black or white
    (WHITE text on a black box shows white); clear() makes the screen white."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            from pybricks.parameters import Color
            from pybricks.tools import wait
            ev3 = EV3Brick()
            ev3.screen.draw_text(5, 5, "Hello")
            wait(100)
            ev3.screen.draw_box(0, 60, 177, 100, fill=True)
            ev3.screen.draw_text(5, 70, 12345, text_color=Color.WHITE)
            wait(100)
            ev3.screen.clear()
            """
        )
    )
    lcd = events(result, "lcd")
    text = frame_at(result, lcd[0][3]["frame"])
    assert (text[5:25, 5:60] == 0).sum() > 20 and (text[30:] == 255).all()
    on_black = frame_at(result, lcd[-2][3]["frame"])
    assert (on_black[70:90, 5:60] == 255).sum() > 20 and (on_black[61:70, 100:] == 0).all()
    assert (last_frame(result) == 255).all()


def test_screen_print_goes_line_by_line_and_scrolls(run):
    """pb_type_ev3dev_image.c ev3dev_Image_print: each line starts a font height below the last, and a line
    that would run off the bottom scrolls the screen up by what it lacks; print's text is black on white.
    With the default font (Font.DEFAULT.height pixels a line), line 1 is at the top; the '\n' that ends
    each print moves to the next line at once, scrolling if need be, so after more lines than fit the
    bottom line is the empty one that comes next and the last line printed is just above it."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            from pybricks.media.ev3dev import Font
            from pybricks.tools import wait
            ev3 = EV3Brick()
            h = Font.DEFAULT.height
            print(h)
            ev3.screen.print("line 1")
            wait(100)
            fit = 128 // h
            for n in range(2, fit + 2):
                ev3.screen.print("line", n)
            """
        )
    )
    height = int(printed(result)[0])
    first = frame_at(result, events(result, "lcd")[0][3]["frame"])
    assert (first[:height] == 0).any() and (first[height:] == 255).all()
    end = last_frame(result)
    assert (end[128 - height :] == 255).all()  # the next line, empty
    assert (end[128 - 2 * height : 128 - height] == 0).any()  # the last line printed
    assert (end[: 128 - (128 // height) * height] == 0).sum() < (first[:height] == 0).sum()  # line 1 is gone


def test_screen_load_image_of_a_png_file_centres_it(run, tmp_path):
    """pb_type_ev3dev_image.c ev3dev_Image_load_image: the screen is cleared and the picture drawn in its
    middle ((178 - w) / 2, (128 - h) / 2); a file name without '.png' gets it (ev3dev_Image_make_new)."""
    from PIL import Image

    picture = Image.new("L", (20, 10), 0)
    picture.save(tmp_path / "block.png")
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            ev3 = EV3Brick()
            ev3.screen.draw_box(0, 0, 10, 10, fill=True)
            ev3.screen.load_image("block")
            """
        )
    )
    end = last_frame(result)
    assert (end[59:69, 79:99] == 0).all()
    assert (end == 0).sum() == 200  # (the box drawn before is cleared)


# ------------------------------------------------------------------------------------------------ speaker
def test_beep_sounds_and_blocks_for_its_duration(run):
    """pb_type_ev3dev_speaker.c ev3dev_Speaker_beep: frequency=500, duration=100 by default; floats are
    truncated (pb_obj_get_int); it waits `duration` ms (mp_hal_delay_ms) and then stops the tone.  The
    speaker starts at its default volumes, Beep 30 % (ev3dev_Speaker_make_new: set_volume(100,
    '_default_'), "sset Beep 77" of 256)."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            from pybricks.tools import StopWatch
            ev3 = EV3Brick()
            watch = StopWatch()
            ev3.speaker.beep()
            t1 = watch.time()
            ev3.speaker.beep(880.7, 250.9)
            print(t1, watch.time())
            """
        )
    )
    assert printed(result) == ["100 350"]  # (the calls themselves cost no time: they are not sysfs)
    beeps = sounds(result, "beep")
    assert [(b["notes"][0]["frequency"], b["notes"][0]["length_ms"]) for b in beeps] == [
        (500, 100),
        (880, 250),
    ]
    assert sounds(result, "set_volume")[0]["pct"] == 30


def test_play_notes_as_the_firmware_plays_them(run):
    """pb_type_ev3dev_speaker.c ev3dev_Speaker_play_note: a whole note is 4 * 60000 / tempo ms, a note
    '/4' a quarter of it, '.' makes it 3/2 as long; an untied note sounds 7/8 of its length and is silent
    for 1/8 ('_' ties it: all sound); the frequency is octave 0's times 2 << octave, so 'A4' sounds at
    880 Hz (the firmware's doubling, one octave above concert A4) and 'C#5' at 17.32 * 64; 'R' rests."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            from pybricks.tools import StopWatch
            ev3 = EV3Brick()
            watch = StopWatch()
            ev3.speaker.play_notes(["A4/4", "C#5/8.", "R/16", "G3/2_"], tempo=60)
            print(watch.time())
            """
        )
    )
    notes = [b["notes"][0] for b in sounds(result, "beep")]
    whole = 4000
    assert [(n["frequency"], n["length_ms"], n["delay_ms"]) for n in notes] == [
        (880, 7 * 1000 // 8, 1000 // 8),
        (int(17.32 * 64), 7 * 750 // 8, 750 // 8),
        (0, 7 * 250 // 8, 250 // 8),
        (int(24.5 * 16), whole // 2, 0),
    ]
    assert printed(result) == [str(875 + 125 + 656 + 93 + 218 + 31 + 2000)]  # (each part in whole ms)


def test_play_notes_errors_are_the_firmwares(run):
    """pb_type_ev3dev_speaker.c ev3dev_Speaker_play_note's ValueErrors, and the firmware's own test of them
    (tests/ev3dev/brick/speaker.py and .exp): a str is iterated note by note ('C' lacks an octave)."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            ev3 = EV3Brick()
            for notes in ('C4/4', ['X'], ['C1'], ['Cb'], ['C#4'], ['Db4/'], ['E#4/4'], ['B#4/4']):
                try:
                    ev3.speaker.play_notes(notes)
                except ValueError as ex:
                    print(ex)
            """
        )
    )
    assert printed(result) == [
        "Missing octave number 2-8",
        "Missing note name A-G or R",
        "Missing octave number 2-8",
        "'Cb' is not allowed",
        "Missing '/'",
        "Missing fractional value 1, 2, 4, 8, etc.",
        "'E#' is not allowed",
        "'B#' is not allowed",
    ]
    assert sounds(result, "beep") == []


def test_say_and_play_file_reach_the_sound_track_and_block(run, tmp_path):
    """pb_type_ev3dev_speaker.c: say() runs espeak (-s 130 words a minute by default) and play_file() aplay,
    each waiting until the subprocess ends; a missing file is RuntimeError('Playing file failed: ...').  A
    .wav file lasts its frames / rate; SoundFile.HELLO (not on this machine) lasts a second here."""
    import wave

    with wave.open(str(tmp_path / "tick.wav"), "wb") as wav:
        wav.setnchannels(1), wav.setsampwidth(1), wav.setframerate(8000)
        wav.writeframes(bytes(4000))
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            from pybricks.media.ev3dev import SoundFile
            from pybricks.tools import StopWatch
            ev3 = EV3Brick()
            watch = StopWatch()
            ev3.speaker.say("one two three")
            t1 = watch.time()
            ev3.speaker.play_file("tick.wav")
            t2 = watch.time()
            ev3.speaker.play_file(SoundFile.HELLO)
            print(t1, t2, watch.time())
            try:
                ev3.speaker.play_file("bad")
            except RuntimeError as ex:
                print(ex)
            """
        )
    )
    out = printed(result)
    said = 3 * 60000 // 130
    assert out[0] == f"{said} {said + 500} {said + 1500}"
    assert out[1] == "Playing file failed: bad: No such file or directory"
    assert sounds(result, "speak")[0]["text"] == "one two three"
    files = sounds(result, "play_file")
    assert [f["wav_file"] for f in files] == ["tick.wav", "/usr/share/sounds/ev3dev/communication/hello.wav"]
    assert files[0]["duration"] == 0.5


def test_set_volume_channels(run):
    """pb_type_ev3dev_speaker.c ev3dev_Speaker_set_volume: volume clamped to 0..100, which= '_all_' (both),
    'Beep' or 'PCM', anything else ValueError.  Beeps play at the Beep volume, files and speech at PCM's."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            ev3 = EV3Brick()
            ev3.speaker.set_volume(150)
            ev3.speaker.beep(duration=10)
            ev3.speaker.set_volume(20, which='Beep')
            ev3.speaker.set_volume(-5, 'PCM')
            ev3.speaker.beep(duration=10)
            ev3.speaker.say("hi")
            try:
                ev3.speaker.set_volume(0, 'bad')
            except ValueError as ex:
                print(ex)
            """
        )
    )
    assert printed(result) == ["which must be one of '_all_', 'Beep', 'PCM'"]
    assert [s["pct"] for s in sounds(result, "set_volume")] == [100, 20, 0]


# ------------------------------------------------------------------------------------------------ buttons, light, battery
def test_buttons_pressed_follow_the_scripted_presses(run):
    """extmod/modbuttons.c buttons_pressed: a list of the Buttons down now, CENTER, LEFT, RIGHT, UP, DOWN,
    LEFT_UP in that order; button_linux_ev3.c: KEY_ENTER is CENTER, KEY_BACKSPACE (the back button)
    LEFT_UP.  buttons is a module of the class (modhubs.c), so EV3Brick.buttons.pressed() works too."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            from pybricks.tools import wait
            ev3 = EV3Brick()
            print(ev3.buttons.pressed())
            wait(1500)
            print(ev3.buttons.pressed())
            wait(1000)
            print(EV3Brick.buttons.pressed())
            """,
            presses=[parse_press("enter@1+1"), parse_press("up@1+1"), parse_press("backspace@2.2+0.5")],
        )
    )
    assert printed(result) == ["[]", "[Button.CENTER, Button.UP]", "[Button.LEFT_UP]"]


def test_light_colours_on_the_red_and_green_leds(run):
    """lib/pbio/drv/ev3dev_stretch/light.c pbdrv_light_get_rgb_for_color and pbdrv_light_set_rgb: RED is
    red 255, GREEN green 255, ORANGE both 255, YELLOW red 30 and green 255, anything else off; both LEDs
    (led0, led1) the same.  modbuiltins.c ColorLight.on: None is BLACK; brightness other than 100 is
    NotImplementedError."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            from pybricks.parameters import Color
            from pybricks.tools import wait
            ev3 = EV3Brick()
            for color in (Color.RED, Color.GREEN, Color.ORANGE, Color.YELLOW, Color.BLUE):
                ev3.light.on(color)
                wait(100)
            ev3.light.on(Color.RED)
            wait(100)
            ev3.light.off()
            try:
                ev3.light.on(Color.RED, 50)
            except NotImplementedError:
                print("NotImplementedError")
            """
        )
    )
    assert printed(result) == ["NotImplementedError"]
    calls = []  # the LEDs after each call: each call writes the four LEDs within a few ms, 100 ms apart
    for t, _, _, leds in events(result, "leds"):
        state = (
            leds["led0:red:brick-status"],
            leds["led0:green:brick-status"],
            leds["led1:red:brick-status"],
        )
        if calls and t - calls[-1][0] < 0.05:
            calls[-1] = (calls[-1][0], state)
        else:
            calls.append((t, state))
    assert [state for _, state in calls] == [
        (255, 0, 255),
        (0, 255, 0),
        (255, 255, 255),
        (30, 255, 30),
        (0, 0, 0),
        (255, 0, 255),
        (0, 0, 0),
    ]


def test_battery_reads_the_power_supply(run):
    """lib/pbio/drv/battery/battery_linux_ev3.c: voltage_now (uV) / 1000 in mV and current_now (uA) / 1000
    in mA, of /sys/class/power_supply/lego-ev3-battery (the simulated battery: 7.8 V, 180 mA); the 1.0
    module's battery is the EV3Brick's (ev3brick.py)."""
    result = check_ok(
        run(
            """
            from pybricks.hubs import EV3Brick
            import pybricks.ev3brick as brick
            print(EV3Brick().battery.voltage(), EV3Brick.battery.current(), brick.battery.voltage())
            """
        )
    )
    assert printed(result) == ["7800 180 7800"]


# ------------------------------------------------------------------------------------------------ 1.0 compatibility
def test_ev3brick_the_1_0_module(run):
    """bricks/ev3dev/modules/pybricks/ev3brick.py: sound is a 1.0 Speaker (speaker.py: beep(frequency=500,
    duration=100, volume=30) sets the Beep volume and blocks; beeps(n) waits 100 ms after each), display a
    1.0 Display (display.py: cleared when made; text() without a location goes 8 px lower each time),
    light(color) the EV3Brick's light, buttons() its pressed buttons (tests/ev3dev/v1/)."""
    result = check_ok(
        run(
            """
            import pybricks.ev3brick as brick
            from pybricks.parameters import Color
            from pybricks.tools import StopWatch
            watch = StopWatch()
            brick.sound.beep(440, 200, 80)
            brick.sound.beeps(2)
            t = watch.time()
            print(t)
            brick.display.text("Hi")
            brick.display.text("there")
            brick.light(Color.GREEN)
            print(brick.buttons())
            """,
            presses=[parse_press("left@0.1+2")],
        )
    )
    assert printed(result)[0] == str(200 + 2 * (100 + 100))
    assert printed(result)[1] == "[Button.LEFT]"
    beeps = [b["notes"][0] for b in sounds(result, "beep")]
    assert [(n["frequency"], n["length_ms"]) for n in beeps] == [(440, 200), (500, 100), (500, 100)]
    assert [s["pct"] for s in sounds(result, "set_volume")][:2] == [80, 30]
    end = last_frame(result)
    assert (end[0:12] == 0).any() and (end[8:20] == 0).any() and (end[30:] == 255).all()
    assert events(result, "leds")[-1][3]["led1:green:brick-status"] == 255


def test_a_run_that_draws_and_plays_repeats_exactly(run):
    """The same program twice: the same LCD frames, sounds, LED changes and printed lines (the trace's
    fingerprint), as every clock the shim reads is the virtual one (DataLog's stamp too)."""
    program = """
        from pybricks.hubs import EV3Brick
        from pybricks.parameters import Color
        from pybricks.tools import DataLog, StopWatch, wait
        ev3 = EV3Brick()
        watch = StopWatch()
        log = DataLog("t")
        for n in range(5):
            ev3.screen.print("n =", n)
            ev3.screen.draw_circle(120, 60, 5 * n)
            ev3.speaker.play_notes(["C4/16", "E4/16"], tempo=240)
            ev3.light.on(Color.GREEN if n % 2 else Color.RED)
            log.log(watch.time())
            wait(30)
        print(repr(log).split())
        """
    first, second = check_ok(run(program)), check_ok(run(program))
    assert first.trace.fingerprint() == second.trace.fingerprint()
    assert len(first.trace.lcd_frames) >= 5
