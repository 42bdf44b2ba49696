"""`hotcut.run` and `hotcut.validate`: the same report as the CLI's report.json, jobs as
paths, RON text and dicts, JobError with the CLI's pointer and line:col, nothing written for
a bad job, Ctrl-C leaving the earlier output whole."""

import hashlib
import json
import os
import pathlib
import re
import signal
import threading
import time

import pytest

import hotcut
from conftest import JOBS, run_cli

# fast jobs of four tasks, two with files relative to the job (curves, design)
SAME_AS_CLI = ["fit-curves", "precut-bump", "hot-blade-facade", "design-vault"]


@pytest.mark.parametrize("name", SAME_AS_CLI)
def test_run_returns_the_report_the_cli_writes(name, cli, tmp_path):
    job = JOBS / f"{name}.ron"
    done = run_cli(cli, job, tmp_path / "cli")
    assert done.returncode == 0, done.stderr
    on_disk = json.loads(next((tmp_path / "cli").glob("*/report.json")).read_text())
    # into a folder, as the CLI does
    assert hotcut.run(job, tmp_path / "py") == on_disk
    files = sorted(p.name for p in next((tmp_path / "py").iterdir()).iterdir())
    cli_files = sorted(p.name for p in next((tmp_path / "cli").iterdir()).iterdir())
    assert files == cli_files
    # in memory: the same report, no file
    assert hotcut.run(str(job)) == on_disk
    # the job as RON text, its relative files found from `base`
    text = job.read_text()
    assert hotcut.run(text, base=JOBS) == on_disk


def test_a_dict_job_runs_like_its_ron_text(cli, tmp_path):
    ron = (
        'Job(name: "wave", surface: HeightField(z: "100*sin(y/200)", x: (0, 400), '
        "y: (0, 1500)), cutting: Cutting(sections: 4), task: Analyze())"
    )
    as_dict = {
        "name": "wave",
        "surface": {"HeightField": {"z": "100*sin(y/200)", "x": (0, 400), "y": [0, 1500]}},
        "cutting": {"sections": 4},
        "task": {"Analyze": {}},
    }
    a, b = hotcut.run(ron), hotcut.run(as_dict)
    assert a == b
    # sin(y/200) changes sign at y = 200π and 400π
    assert len(a["sections"][0]["inflections"]) == 2
    path = tmp_path / "wave.ron"
    path.write_text(ron)
    done = run_cli(cli, path, tmp_path / "cli")
    assert done.returncode == 0, done.stderr
    assert json.loads((tmp_path / "cli" / "wave" / "report.json").read_text()) == a
    v = hotcut.validate(as_dict)
    assert v["name"] == "wave" and v["task"] == "Analyze"


def _dir_hash(d):
    h = hashlib.sha256()
    for p in sorted(pathlib.Path(d).rglob("*")):
        h.update(str(p.relative_to(d)).encode())
        if p.is_file():
            h.update(p.read_bytes())
    return h.hexdigest()


BAD = [
    # (job, pointer, line, col) — a RON text's errors carry line and column
    ('Job(name: "x", surface: HeightField(z: "x", x: (0, 1), y: (0, 1)),\n task: Analyze(), bogus: 1)',
     "/bogus", 2, 19),
    ('Job(name: "x", surface: HeightField(z: "x", x: (0, 1), y: (0, 1)),\n task: Analyze(samples: "many"))',
     "/task/Analyze/samples", 2, 24),
    ({"name": "x", "surface": {"HeightField": {"z": "x", "x": [0, 1], "y": [0, 1]}},
      "task": {"Analyze": {}}, "cutting": {"sections": 0}}, "/cutting/sections", None, None),
    ({"name": "x", "surface": {"HeightField": {"z": "x", "x": [0, 1], "y": [0, 1]}},
      "task": {"Analyze": {}}, "tolerance": {"rms": float("nan")}}, "/tolerance/rms", None, None),
    ({"name": "x", "surface": {"Mesh": {"path": "no-such-file.obj"}}, "task": {"Analyze": {}}},
     "/surface/Mesh/path", None, None),
    ({"name": "x", "surface": {"HeightField": {"z": "x +", "x": [0, 1], "y": [0, 1]}},
      "task": {"Analyze": {}}}, "/surface/HeightField/z", None, None),
]


@pytest.mark.parametrize("job,pointer,line,col", BAD)
def test_a_bad_job_raises_job_error_with_its_pointer_and_writes_nothing(job, pointer, line, col, tmp_path):
    for call in (lambda: hotcut.validate(job), lambda: hotcut.run(job, tmp_path / "out")):
        with pytest.raises(hotcut.JobError) as e:
            call()
        err = e.value
        assert isinstance(err, hotcut.HotcutError)
        assert err.pointer == pointer, str(err)
        assert (err.line, err.col) == (line, col), str(err)
        assert pointer in str(err) and err.message in str(err)
        assert err.errors and err.errors[0]["pointer"] == pointer
        if line is not None:
            assert f":{line}:{col}:" in str(err)
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_the_cli_prints_the_same_error(cli, tmp_path):
    text = BAD[0][0]
    path = tmp_path / "bad.ron"
    path.write_text(text)
    done = run_cli(cli, path, tmp_path / "out")
    assert done.returncode == 1
    with pytest.raises(hotcut.JobError) as e:
        hotcut.run(path)
    assert str(e.value) in done.stderr


def test_other_job_arguments():
    with pytest.raises(hotcut.JobError) as e:
        hotcut.run("no/such/job.ron")
    assert "no/such/job.ron" in str(e.value)
    with pytest.raises(TypeError):
        hotcut.run(42)
    with pytest.raises(hotcut.JobError) as e:
        hotcut.run({"name": "x", 3: "y"})
    assert "keys must be strings" in str(e.value)
    cyclic = {"name": "x"}
    cyclic["task"] = cyclic
    with pytest.raises(hotcut.JobError):
        hotcut.run(cyclic)
    with pytest.raises(ValueError):
        hotcut.run(JOBS / "precut-bump.ron", max_work=0)


def test_progress_is_reported_and_a_raising_callback_stops_the_run(tmp_path):
    seen = []
    hotcut.run(JOBS / "seg-wavy-inflection.ron", progress=lambda *a: seen.append(a))
    assert seen and all(isinstance(l, str) and d >= 0 for l, d, _ in seen)

    class Stop(Exception):
        pass

    def stop(*_):
        raise Stop

    with pytest.raises(Stop):
        hotcut.run(JOBS / "blocks-torus.ron", tmp_path, progress=stop)
    _wait_idle()
    assert not any(tmp_path.iterdir()), list(tmp_path.iterdir())


def _wait_idle(limit=1.0):
    start = time.monotonic()
    while hotcut._native._active_runs() and time.monotonic() - start < limit:
        time.sleep(0.01)
    return time.monotonic() - start


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals")
def test_ctrl_c_stops_the_run_within_a_second_and_keeps_the_old_output(tmp_path):
    job = JOBS / "blocks-torus.ron"
    hotcut.run(job, tmp_path)
    (folder,) = [p for p in tmp_path.iterdir()]
    before = _dir_hash(folder)
    sent = {}

    def interrupt():
        time.sleep(0.6)
        sent["at"] = time.monotonic()
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=interrupt, daemon=True).start()
    with pytest.raises(KeyboardInterrupt):
        hotcut.run(job, tmp_path)
    raised = time.monotonic() - sent["at"]
    assert raised < 1.0, f"KeyboardInterrupt {raised:.2f} s after Ctrl-C"
    # the run itself stops too, not only the call
    stopped = _wait_idle() + raised
    assert hotcut._native._active_runs() == 0
    assert stopped < 1.0, f"the run went on {stopped:.2f} s after Ctrl-C"
    assert [p.name for p in tmp_path.iterdir()] == [folder.name], "a temporary folder was left"
    assert _dir_hash(folder) == before
    # and the next run works
    assert hotcut.run(job)


def test_nothing_to_cut_raises_run_error_with_the_report(tmp_path):
    # no piecewise ruled surface comes within 0.01 mm of the wave: RuledBlocks refuses,
    # writes its report and page, and no G-code
    job = (JOBS / "ruled-wave.ron").read_text()
    job = job.replace("Tolerance(max: 3.0)", "Tolerance(max: 0.01)")
    job = job.replace("RuledBlocks(sections: 24, max_strips: 48, grid: 48, max_iterations: 10)",
                      "RuledBlocks(sections: 8, max_strips: 2, grid: 24, max_iterations: 4)")
    with pytest.raises(hotcut.RunError) as e:
        hotcut.run(job)
    assert "nothing to cut" in str(e.value) and "tolerance.max" in str(e.value)
    assert isinstance(e.value.report, dict) and e.value.report
    with pytest.raises(hotcut.RunError):
        hotcut.run(job, tmp_path)
    written = sorted(p.name for p in (tmp_path / "ruled-wave").iterdir())
    assert not any(n.endswith(".gcode") for n in written) and "report.json" in written


def test_run_releases_the_gil():
    done = threading.Event()
    result = {}

    def work():
        result["report"] = hotcut.run(JOBS / "seg-wavy-inflection.ron")
        done.set()

    t = threading.Thread(target=work)
    t.start()
    time.sleep(0.05)
    # while the run goes on, this thread keeps running Python
    counted, start = 0, time.monotonic()
    while not done.is_set() and time.monotonic() - start < 0.3:
        counted += 1
    t.join()
    assert result["report"]
    assert counted > 10_000, f"only {counted} loops ran beside the run: the GIL was held"
