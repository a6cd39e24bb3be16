"""Sound: each sound is one _link call, and waiting for it takes its (virtual) duration."""

import wave

import pytest

from ev3dev2.sound import Sound


@pytest.fixture
def brick(make_brick):
    return make_brick()


def sounds(brick):
    return [tuple(call[1:]) for call in brick.calls if call[0] == "sound"]


def test_beep_plays_beeps_default_tone_and_waits(brick):
    start = brick.clock
    assert Sound().beep() is None

    assert sounds(brick) == [
        (
            "beep",
            {
                "args": "",
                "notes": [
                    {"frequency": 440, "length_ms": 200, "delay_ms": 100, "repeats": 1, "end_delay": False}
                ],
                "duration": 0.2,
                "play_type": 0,
            },
        )
    ]
    assert brick.clock - start == pytest.approx(0.2)


def test_tone_sequence_becomes_one_beep_command(brick):
    start = brick.clock
    Sound().tone([(392, 350, 100), (440, 200)])

    kind, details = sounds(brick)[0]
    assert kind == "beep"
    assert details["args"] == "-f 392 -l 350 -D 100  -n -f 440 -l 200 "
    assert [(n["frequency"], n["length_ms"]) for n in details["notes"]] == [(392, 350), (440, 200)]
    assert brick.clock - start == pytest.approx(0.55)  # beep's -D only separates repeats of one note


def test_play_tone_sets_the_volume_first(brick):
    Sound().play_tone(440, 0.5, volume=50)

    assert [kind for kind, _ in sounds(brick)] == ["set_volume", "beep"]
    assert sounds(brick)[0][1] == {"pct": 50, "channel": "Playback"}
    assert sounds(brick)[1][1]["args"] == "-f 440 -l 500 -D 0 "


def test_play_note_and_its_errors(brick):
    spkr = Sound()
    assert spkr.play_note("A4", 0.25) is None
    assert sounds(brick)[-1][1]["notes"][0]["frequency"] == 440

    with pytest.raises(ValueError, match=r"^invalid note \(a4\)$"):
        spkr.play_note("a4", 1)  # upstream looks the exact name up before trying it upper-cased

    with pytest.raises(ValueError, match=r"^invalid note \(H9\)$"):
        spkr.play_note("H9", 1)
    with pytest.raises(ValueError, match=r"^invalid duration \(0\)$"):
        spkr.play_note("C4", 0)
    with pytest.raises(ValueError, match=r"^invalid volume \(101\)$"):
        spkr.play_tone(440, 1, volume=101)
    with pytest.raises(AssertionError, match="^Invalid play_type 7, must be one of 0,1,2$"):
        spkr.play_tone(440, 1, play_type=7)


def test_play_song_beeps_notes_and_sleeps_rests(brick):
    start = brick.clock
    Sound().play_song((("D4", "e3"), ("R", "q"), ("G4", "h")))

    assert [details["args"] for _, details in sounds(brick)] == [
        "-f 294 -l 166 -D 50",
        "-f 392 -l 1000 -D 50",
    ]
    assert brick.clock - start == pytest.approx(0.166 + 0.55 + 1.0)
    with pytest.raises(ValueError, match=r"^invalid note \(x\)$"):
        Sound().play_song((("C4", "x"),))


def test_no_wait_returns_a_process_to_wait_for(brick):
    start = brick.clock
    process = Sound().beep("-f 300 -l 1000", play_type=Sound.PLAY_NO_WAIT_FOR_COMPLETE)

    assert brick.clock == start
    assert process.poll() is None
    assert process.wait() == 0
    assert brick.clock - start == pytest.approx(1)


def test_speak_takes_about_as_long_as_espeak(brick):
    start = brick.clock
    Sound().speak("hello world robot")

    assert sounds(brick)[-1][0] == "speak"
    assert sounds(brick)[-1][1]["text"] == "hello world robot"
    assert brick.clock - start == pytest.approx(3 * 60 / 130)


def test_play_file_checks_the_file_and_waits_for_its_length(brick, tmp_path):
    path = str(tmp_path / "bark.wav")
    with wave.open(path, "wb") as wav:
        wav.setnchannels(1)
        wav.setsampwidth(1)
        wav.setframerate(8000)
        wav.writeframes(b"\x80" * 4000)
    start = brick.clock

    Sound().play_file(path, volume=80)

    assert sounds(brick)[-1][0] == "play_file"
    assert brick.clock - start == pytest.approx(0.5)
    with pytest.raises(ValueError, match="does not exist$"):
        Sound().play_file(str(tmp_path / "missing.wav"))
    with pytest.raises(ValueError, match=r"only \.wav files are supported$"):
        Sound().play_file(str(tmp_path / "song.mp3"))


def test_volume(brick):
    spkr = Sound()
    spkr.set_volume(30)
    assert spkr.get_volume() == 30
    with pytest.raises(ValueError):
        spkr.set_volume(30.5)  # amixer's argument is formatted with {:d}, as upstream
