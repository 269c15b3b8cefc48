"""Outputs that must not damage what they replace, output sets written all or nothing, worker
processes that end with the command, and inputs read only when they are regular files, and only
up to a limit (issue 24).

Each case checks its post-condition, not only the exit status: the special file an output was
given is still a device, a FIFO or a link afterwards; a folder holds afterwards exactly what it
held before a failed command; an earlier ``variants`` run is intact after a failed ``--force``;
no process of the command is alive after it exits.

Devices are private twins made with ``mknod`` in the test's folder (``/dev/null`` is 1:3,
``/dev/full`` 1:7), never the machine's own, so that a regression damages nothing outside the
test; they need CAP_MKNOD (root here), and the cases skip without it.
"""

from __future__ import annotations

import contextlib
import json
import os
import select
import signal
import socket
import stat
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import pytest

from planmethod.cli import main
from planmethod.errors import PlanmethodError
from planmethod.io import output_set, read_bytes_bounded
from planmethod.testing.processes import processes_holding

ROOT = Path(__file__).resolve().parent.parent
GOOD = str(ROOT / "exercises" / "compressor_slider_crank.toml")
STUDY = str(ROOT / "exercises" / "fourbar_study.toml")
FOURBAR = ROOT / "exercises" / "fourbar_forces.toml"
CONVEYOR = str(ROOT / "exercises" / "conveyor_sixbar.toml")
TABLE = ROOT / "exercises" / "conveyor_sixbar_table2.csv"
TEMPLATE = str(ROOT / "exercises" / "templates" / "slider_crank.toml")


def _fails(capfd, argv: list) -> str:
    """Run ``argv`` in-process: exit 2, one line on stderr, no traceback; returns the line."""
    code = main([str(a) for a in argv])
    out, err = capfd.readouterr()
    assert code == 2, (argv, code, out[-300:], err[-300:])
    assert "Traceback" not in out + err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("planmethod") and ": error: " in lines[0], err
    return lines[0]


def _tree(folder: Path) -> dict[str, bytes | str]:
    """Every entry under ``folder`` (hidden ones too): a regular file's bytes, else what it is
    (a link's target, "folder", or the file type of a device, FIFO or socket)."""
    def entry(path: Path) -> bytes | str:
        mode = os.lstat(path).st_mode
        if stat.S_ISLNK(mode):
            return f"link to {os.readlink(path)}"
        if stat.S_ISREG(mode):
            return path.read_bytes()
        return "folder" if stat.S_ISDIR(mode) else f"special {stat.S_IFMT(mode)}"

    return {str(path.relative_to(folder)): entry(path) for path in sorted(folder.rglob("*"))}


@pytest.fixture
def private_temp(tmp_path, monkeypatch) -> Path:
    """The folder Python's tempfile uses during the test (content for devices is staged
    there): empty again after every command."""
    folder = tmp_path / "tempdir"
    folder.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(folder))
    return folder


def _device(path: Path, minor: int) -> Path:
    """A private twin of /dev/null (minor 3) or /dev/full (minor 7) at ``path``."""
    try:
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, minor))
    except PermissionError:
        pytest.skip("making a device needs CAP_MKNOD (root)")
    return path


class FifoReader:
    """A reader on a FIFO: holds its read end open and collects what is written into it."""

    def __init__(self, path: Path) -> None:
        self.descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
        self.chunks: list[bytes] = []
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self) -> None:
        while not self.stop.is_set():
            if select.select([self.descriptor], [], [], 0.05)[0]:
                try:
                    chunk = os.read(self.descriptor, 1 << 16)
                except BlockingIOError:
                    continue
                if chunk:
                    self.chunks.append(chunk)
                else:
                    time.sleep(0.01)   # no writer at the moment

    def close(self) -> bytes:
        self.stop.set()
        self.thread.join()
        with contextlib.suppress(BlockingIOError):
            while chunk := os.read(self.descriptor, 1 << 16):
                self.chunks.append(chunk)
        os.close(self.descriptor)
        return b"".join(self.chunks)


# ---------------------------------------------------------------------------------------------
# outputs that exist and are not regular files

#: command → (argv with OUT for the output, the output's suffix)
SINGLE_OUTPUTS: dict[str, tuple[list[str], str]] = {
    "sweep --csv": (["sweep", GOOD, "--step", "30", "--csv", "OUT"], ".csv"),
    "sweep --plot": (["sweep", GOOD, "--step", "30", "--plot", "OUT"], ".svg"),
    "study --csv": (["study", STUDY, "--step", "90", "--csv", "OUT"], ".csv"),
    "grade --csv": (["grade", GOOD, "ANSWERS", "--csv", "OUT"], ".csv"),
    "grade --json": (["grade", GOOD, "ANSWERS", "--json", "OUT"], ".json"),
    "export moodle": (["export", GOOD, "--format", "moodle", "--out", "OUT"], ".xml"),
    "workbook": (["workbook", GOOD, "-o", "OUT", "--step", "90"], ".html"),
    "animate": (["animate", GOOD, "-o", "OUT", "--step", "90"], ".svg"),
}


def _argv(case: str, out: Path, folder: Path) -> list[str]:
    answers = folder / "answers.csv"
    if not answers.exists():
        answers.write_text("student,v_C\ns1,5\n")
    return [str(out) if a == "OUT" else str(answers) if a == "ANSWERS" else a
            for a in SINGLE_OUTPUTS[case][0]]


@pytest.mark.parametrize("case", list(SINGLE_OUTPUTS))
def test_a_device_output_stays_a_device(capfd, tmp_path, private_temp, case):
    """As ``cmd > /dev/null``: written in place, through a link named with the suffix the
    command asks; the device is still a device and the link still a link."""
    device = _device(tmp_path / "null", 3)
    out = tmp_path / f"out{SINGLE_OUTPUTS[case][1]}"
    out.symlink_to(device)
    assert main(_argv(case, out, tmp_path)) == 0, capfd.readouterr().err
    assert out.is_symlink() and stat.S_ISCHR(os.stat(device).st_mode)
    assert os.stat(device).st_rdev == os.makedev(1, 3)
    assert list(private_temp.iterdir()) == []


@pytest.mark.parametrize("case", list(SINGLE_OUTPUTS))
def test_a_fifo_output_gets_the_file_and_stays_a_fifo(capfd, tmp_path, private_temp, case):
    """Into a FIFO that a program reads: the reader gets exactly the bytes the command writes
    into a regular file, and the FIFO is still a FIFO."""
    regular = tmp_path / f"regular{SINGLE_OUTPUTS[case][1]}"
    assert main(_argv(case, regular, tmp_path)) == 0
    fifo = tmp_path / f"pipe{SINGLE_OUTPUTS[case][1]}"
    os.mkfifo(fifo)
    reader = FifoReader(fifo)
    try:
        assert main(_argv(case, fifo, tmp_path)) == 0, capfd.readouterr().err
    finally:
        received = reader.close()
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert received == regular.read_bytes() and received
    assert list(private_temp.iterdir()) == []


@pytest.mark.parametrize("case", ["sweep --csv", "grade --json", "export moodle", "workbook"])
def test_a_link_to_the_standard_output_writes_into_it(capfd, tmp_path, private_temp, case):
    """A link to /proc/self/fd/1 (as /dev/stdout is): the content goes into the standard
    output, the link stays a link."""
    regular = tmp_path / f"regular{SINGLE_OUTPUTS[case][1]}"
    assert main(_argv(case, regular, tmp_path)) == 0
    capfd.readouterr()
    out = tmp_path / f"stdout{SINGLE_OUTPUTS[case][1]}"
    out.symlink_to("/proc/self/fd/1")
    assert main(_argv(case, out, tmp_path)) == 0
    printed = capfd.readouterr().out
    assert out.is_symlink() and os.readlink(out) == "/proc/self/fd/1"
    assert regular.read_text(encoding="utf-8") in printed
    assert list(private_temp.iterdir()) == []


def test_a_full_device_is_one_line(capfd, tmp_path, private_temp):
    device = _device(tmp_path / "full", 7)
    line = _fails(capfd, ["sweep", GOOD, "--step", "30", "--csv", device])
    assert "No space left on device" in line and str(device) in line
    assert stat.S_ISCHR(os.stat(device).st_mode)
    assert list(private_temp.iterdir()) == []


def test_a_full_device_in_a_set_leaves_the_other_file_alone(capfd, tmp_path, private_temp):
    """grade --json FILE --csv /dev/full: the device refuses, so the JSON is not written."""
    device = _device(tmp_path / "full.csv", 7)
    (tmp_path / "answers.csv").write_text("student,v_C\ns1,5\n")
    (tmp_path / "g.json").write_text("earlier")
    before = _tree(tmp_path)
    _fails(capfd, ["grade", GOOD, tmp_path / "answers.csv", "--json", tmp_path / "g.json",
                   "--csv", device])
    assert _tree(tmp_path) == before and stat.S_ISCHR(os.stat(device).st_mode)


def test_a_fifo_that_nothing_reads_is_refused_at_once(tmp_path):
    """A real process, so that a regression hangs no test run: one line, exit 2 at once (no
    waiting for a reader), the FIFO still a FIFO."""
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    done = subprocess.run([sys.executable, "-m", "planmethod", "sweep", GOOD, "--step", "30",
                           "--csv", str(fifo)], capture_output=True, text=True, cwd=ROOT,
                          timeout=120)
    assert done.returncode == 2 and "nothing reads" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and sorted(tmp_path.iterdir()) == [fifo]


def test_a_socket_output_is_refused(capfd, tmp_path):
    path = tmp_path / "s.csv"
    server = socket.socket(socket.AF_UNIX)
    try:
        server.bind(str(path))
        line = _fails(capfd, ["sweep", GOOD, "--step", "30", "--csv", path])
        assert "socket" in line and stat.S_ISSOCK(os.lstat(path).st_mode)
    finally:
        server.close()
    assert sorted(tmp_path.iterdir()) == [path]


def test_a_link_to_a_regular_file_stays_a_link(tmp_path, capfd):
    real = tmp_path / "real.csv"
    real.write_text("earlier")
    link = tmp_path / "link.csv"
    link.symlink_to(real.name)
    assert main(["sweep", GOOD, "--step", "30", "--csv", str(link)]) == 0
    assert link.is_symlink() and real.read_text().startswith("angle")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.csv", "real.csv"]


# ---------------------------------------------------------------------------------------------
# output sets: all or nothing, no folder left behind


def test_solve_svg_with_a_folder_in_the_way_writes_no_drawing(capfd, tmp_path):
    figures = tmp_path / "svg"
    (figures / "velocity.svg").mkdir(parents=True)
    line = _fails(capfd, ["solve", GOOD, "--svg", figures])
    assert "velocity.svg" in line and "folder" in line
    assert sorted(p.name for p in figures.iterdir()) == ["velocity.svg"]
    assert list((figures / "velocity.svg").iterdir()) == []


def test_a_sweep_that_cannot_turn_leaves_no_folder(capfd, tmp_path, monkeypatch):
    """A four-bar whose crank (0.20 m) is too long to turn: the error comes while the CSV is
    being written, and neither the CSV nor its new folder n1/ is left."""
    stuck = tmp_path / "stuck.toml"
    stuck.write_text(FOURBAR.read_text(encoding="utf-8").replace(
        "B = [0.08, 0]", "B = [0.20, 0]"), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    line = _fails(capfd, ["sweep", "stuck.toml", "--step", "10", "--csv", "n1/s.csv"])
    assert "cannot join" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["stuck.toml"]


def test_a_slug_too_long_for_a_folder_leaves_no_folder(capfd, tmp_path):
    line = _fails(capfd, ["export", GOOD, "--format", "prairielearn", "--out", tmp_path / "pl",
                          "--slug", "q" * 300])
    assert "--slug" in line and "255" in line
    assert list(tmp_path.iterdir()) == []


def test_a_plot_is_not_written_without_its_csv(capfd, tmp_path):
    (tmp_path / "t.csv").mkdir()
    _fails(capfd, ["sweep", GOOD, "--step", "30", "--plot", tmp_path / "c.png", "--csv",
                   tmp_path / "t.csv"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.csv"]


def test_grade_writes_none_of_its_outputs_when_one_fails(capfd, tmp_path):
    (tmp_path / "answers.csv").write_text("student,v_C\ns1,5\n")
    (tmp_path / "report").write_text("a file where the report folder should be")
    before = _tree(tmp_path)
    line = _fails(capfd, ["grade", GOOD, tmp_path / "answers.csv", "--json",
                          tmp_path / "new" / "g.json", "--csv", tmp_path / "g.csv", "--report",
                          tmp_path / "report"])
    assert "not a folder" in line
    assert _tree(tmp_path) == before


def _fail_call(monkeypatch, name: str, number: int, error: OSError) -> None:
    """Make the ``number``-th call of ``os.<name>`` raise ``error`` (the others work)."""
    real = getattr(os, name)
    calls = []

    def failing(*arguments, **keywords):
        calls.append(arguments)
        if len(calls) == number:
            raise error
        return real(*arguments, **keywords)

    monkeypatch.setattr(os, name, failing)


def test_a_failed_rename_undoes_the_set(tmp_path, monkeypatch):
    """The second rename of a commit fails: the first file gets its earlier content back, and
    the folder the commit made is removed."""
    (tmp_path / "a.txt").write_text("earlier a")
    before = _tree(tmp_path)
    _fail_call(monkeypatch, "replace", 2, OSError(28, "No space left on device"))
    with pytest.raises(PlanmethodError, match="No space left"), output_set() as outputs:
        outputs.text(tmp_path / "a.txt", "new a")
        outputs.text(tmp_path / "new" / "b.txt", "new b")
    monkeypatch.undo()
    assert _tree(tmp_path) == before


def test_a_set_given_one_file_twice_is_refused(tmp_path):
    with pytest.raises(PlanmethodError, match="twice"), output_set() as outputs:
        outputs.text(tmp_path / "a.csv", "1")
        outputs.text(tmp_path / "." / "a.csv", "2")
    assert list(tmp_path.iterdir()) == []


def test_a_set_stages_nothing_outside_its_folder_through_a_link(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "q").symlink_to(outside)
    with pytest.raises(ValueError, match="leads out"), output_set() as outputs:
        outputs.files(tmp_path / "out", {"q/info.json": "{}"})
    assert list(outside.iterdir()) == []


# ---------------------------------------------------------------------------------------------
# variants --force


def _variants(count: int, out: Path, *extra: str) -> list[str]:
    return ["variants", TEMPLATE, "--out", str(out), "--no-sheets", "--count", str(count),
            *extra]


@pytest.fixture
def earlier_run(tmp_path, capfd) -> Path:
    """An earlier run of three variants in tmp_path/run."""
    out = tmp_path / "run"
    assert main(_variants(3, out)) == 0
    capfd.readouterr()
    return out


def test_force_replaces_an_earlier_run_and_removes_only_it(tmp_path, capfd, earlier_run):
    (tmp_path / "beside.txt").write_text("not in the run")
    assert main(_variants(2, earlier_run, "--force")) == 0
    assert sorted(p.name for p in earlier_run.iterdir()) == [
        "001", "002", "index.csv", "keys.json", "manifest.json"]
    assert json.loads((earlier_run / "keys.json").read_text())["count"] == 2
    assert (tmp_path / "beside.txt").read_text() == "not in the run"


def test_force_never_follows_a_linked_variant_folder(tmp_path, capfd, earlier_run):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "key.json").write_text("someone else's")
    for name in os.listdir(earlier_run / "002"):
        os.unlink(earlier_run / "002" / name)
    (earlier_run / "002").rmdir()
    (earlier_run / "002").symlink_to(elsewhere)
    before = _tree(tmp_path)
    line = _fails(capfd, _variants(3, earlier_run, "--force"))
    assert "symbolic link" in line and "002" in line
    assert _tree(tmp_path) == before and (earlier_run / "002").is_symlink()


def test_an_edited_index_never_deletes_the_file_it_names(tmp_path, capfd, earlier_run):
    (earlier_run / "notes.txt").write_text("mine")
    with (earlier_run / "index.csv").open("a") as index:
        index.write("x,notes.txt,0,{}\n")
    before = _tree(tmp_path)
    line = _fails(capfd, _variants(3, earlier_run, "--force"))
    assert "notes.txt" in line
    assert _tree(tmp_path) == before
    (earlier_run / "notes.txt").unlink()    # the edited index alone is refused too
    line = _fails(capfd, _variants(3, earlier_run, "--force"))
    assert "index.csv changed" in line and (earlier_run / "001" / "key.json").is_file()


def test_a_manifest_naming_another_file_is_refused(tmp_path, capfd, earlier_run):
    (earlier_run / "notes.txt").write_text("mine")
    manifest = json.loads((earlier_run / "manifest.json").read_text())
    manifest["files"].append(["notes.txt", 4, "0" * 64])
    (earlier_run / "manifest.json").write_text(json.dumps(manifest))
    before = _tree(tmp_path)
    line = _fails(capfd, _variants(3, earlier_run, "--force"))
    assert "notes.txt" in line and _tree(tmp_path) == before


def test_an_edited_key_is_not_removed(tmp_path, capfd, earlier_run):
    (earlier_run / "002" / "key.json").write_text("{}")
    before = _tree(tmp_path)
    line = _fails(capfd, _variants(3, earlier_run, "--force"))
    assert "002/key.json changed" in line and _tree(tmp_path) == before


def test_a_folder_without_a_manifest_is_not_replaced(tmp_path, capfd, earlier_run):
    (earlier_run / "manifest.json").unlink()
    before = _tree(tmp_path)
    line = _fails(capfd, _variants(3, earlier_run, "--force"))
    assert "manifest.json" in line and _tree(tmp_path) == before


def test_a_run_that_fails_while_written_leaves_the_earlier_one(tmp_path, earlier_run):
    """A real process whose files may not exceed 40 kB (RLIMIT_FSIZE): the student files are
    written, keys.json (about 60 kB) fails. The earlier run is intact and nothing staged is
    left (no hidden folder)."""
    import resource

    def small_files() -> None:
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)   # a write past the limit fails (EFBIG)
        resource.setrlimit(resource.RLIMIT_FSIZE, (40_000, 40_000))

    before = _tree(tmp_path)
    done = subprocess.run([sys.executable, "-m", "planmethod",
                           *_variants(3, earlier_run, "--force")], capture_output=True,
                          text=True, cwd=ROOT, timeout=300, preexec_fn=small_files)
    assert done.returncode == 2 and "File too large" in done.stderr, done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    assert _tree(tmp_path) == before


def test_a_swap_that_fails_midway_is_undone(tmp_path, capfd, earlier_run, monkeypatch):
    """The third move of the swap fails: every entry goes back, the earlier run is intact."""
    before = _tree(tmp_path)
    _fail_call(monkeypatch, "rename", 3, OSError(5, "Input/output error"))
    line = _fails(capfd, _variants(2, earlier_run, "--force"))
    monkeypatch.undo()
    assert "Input/output error" in line and _tree(tmp_path) == before


def test_the_run_is_never_mixed_with_files_added_during_it(tmp_path, capfd, earlier_run,
                                                          monkeypatch):
    """A file the user adds into the earlier run's folder while the new run is computed stays
    (in the moved-aside folder, which the note names)."""
    from planmethod.grading import keys

    real_build_key = keys.build_key

    def build_key_adding_a_file(variant):
        extra = earlier_run / "001" / "added.txt"
        if not extra.exists():
            extra.write_text("added during the run")
        return real_build_key(variant)

    monkeypatch.setattr(keys, "build_key", build_key_adding_a_file)
    assert main(_variants(2, earlier_run, "--force")) == 0
    err = capfd.readouterr().err
    kept = [path for path in earlier_run.rglob("added.txt")]
    assert len(kept) == 1 and kept[0].read_text() == "added during the run"
    assert "keeps" in err and "001" in err


# ---------------------------------------------------------------------------------------------
# workbook --jobs: bounded, and no worker outlives the command


def test_jobs_above_the_cpus_is_one_line(capfd, tmp_path):
    from planmethod.application.workers import usable_cpus

    line = _fails(capfd, ["workbook", GOOD, "-o", tmp_path / "w.html", "--step", "90",
                          "--jobs", str(usable_cpus() + 1)])
    assert "--jobs" in line and f"1…{usable_cpus()}" in line
    assert list(tmp_path.iterdir()) == []


def test_never_more_workers_than_frames():
    from planmethod.application.workers import usable_cpus, worker_count

    assert worker_count(usable_cpus(), 1) == 1
    assert worker_count(None, 4) == 1
    assert worker_count(1, 360) == 1


@pytest.mark.skipif(not Path("/proc/self/cmdline").exists(), reason="needs /proc")
def test_sigterm_ends_the_workbook_and_its_workers(tmp_path):
    """SIGTERM to the main process alone, mid-run with two workers: it exits (143) within
    2 s, and no process of it is left."""
    from planmethod.application.workers import usable_cpus

    if usable_cpus() < 2:
        pytest.skip("two workers need two CPUs")
    page = tmp_path / "marker-page.html"
    process = subprocess.Popen([sys.executable, "-m", "planmethod", "workbook", GOOD, "-o",
                                str(page), "--step", "0.5", "--jobs", "2"], cwd=ROOT,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120

        def workers() -> list[int]:
            return [pid for pid in processes_holding(str(page)) if pid != process.pid]

        while len(workers()) < 2 and time.monotonic() < deadline:
            time.sleep(0.05)
        assert len(workers()) == 2, "the workers never started"
        time.sleep(0.5)                 # they are solving frames now
        assert process.poll() is None
        process.send_signal(signal.SIGTERM)
        sent = time.monotonic()
        _, err = process.communicate(timeout=60)
        took = time.monotonic() - sent
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == 143 and err.strip() == "planmethod: terminated"
    assert took <= 2.0, f"took {took:.1f} s to end"
    assert processes_holding(str(page)) == []
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------------------------------------
# inputs: regular files only, read up to a limit

#: input → argv with IN for the input (FOLDER: the test's folder)
INPUTS: dict[str, list[str]] = {
    "exercise (solve)": ["solve", "IN"],
    "exercise (sweep)": ["sweep", "IN", "--step", "90"],
    "template (variants)": ["variants", "IN", "--out", "FOLDER/run"],
    "roster (variants)": ["variants", TEMPLATE, "--students", "IN", "--out", "FOLDER/run"],
    "answers (grade)": ["grade", GOOD, "IN"],
    "drawing (grade)": ["grade", GOOD, "--drawing", "IN", "--plan", "velocity"],
    "key (grade)": ["grade", "IN", "FOLDER/answers.csv"],
    "coordinates (check)": ["check", CONVEYOR, "IN"],
    "answers (export)": ["export", GOOD, "--format", "csv", "--answers", "IN", "--out",
                         "FOLDER/g.csv"],
}

#: what a key input needs to be read as one (by its suffix)
SUFFIXES = {"key (grade)": ".json", "template (variants)": ".toml"}


def _input_argv(argv: list[str], path: Path, folder: Path) -> list[str]:
    (folder / "answers.csv").write_text("student,v_C\ns1,5\n")
    return [str(path) if a == "IN" else a.replace("FOLDER", str(folder)) for a in argv]


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
@pytest.mark.parametrize("case", list(INPUTS))
def test_an_endless_device_is_refused(capfd, tmp_path, case, device):
    """Through a link with the input's suffix, so that nothing but the read tells it apart."""
    link = tmp_path / f"input{SUFFIXES.get(case, '.csv')}"
    link.symlink_to(device)
    argv = _input_argv(INPUTS[case], link, tmp_path)
    before = _tree(tmp_path)
    line = _fails(capfd, argv)
    assert str(link) in line and "character device" in line
    assert _tree(tmp_path) == before


@pytest.mark.parametrize("case", list(INPUTS))
def test_a_fifo_input_is_refused_without_waiting(capfd, tmp_path, case):
    """A FIFO with no writer: refused at once. If a read ever blocked on it, a watchdog opens
    the write end after 20 s so that the test fails instead of hanging."""
    fifo = tmp_path / f"input{SUFFIXES.get(case, '.csv')}"
    os.mkfifo(fifo)
    finished = threading.Event()

    def watchdog() -> None:
        if not finished.wait(20):
            descriptor = os.open(fifo, os.O_WRONLY | os.O_NONBLOCK)
            os.close(descriptor)

    guard = threading.Thread(target=watchdog, daemon=True)
    guard.start()
    argv = _input_argv(INPUTS[case], fifo, tmp_path)
    before = _tree(tmp_path)
    started = time.monotonic()
    try:
        line = _fails(capfd, argv)
    finally:
        finished.set()
        guard.join()
    assert time.monotonic() - started < 20
    assert str(fifo) in line and "FIFO" in line and _tree(tmp_path) == before


def test_a_moodle_sheet_that_is_a_device_is_refused(capfd, tmp_path):
    run = tmp_path / "run"
    assert main(["variants", TEMPLATE, "--out", str(run), "--count", "1"]) == 0
    capfd.readouterr()
    (run / "001" / "task.svg").unlink()
    (run / "001" / "task.svg").symlink_to("/dev/zero")
    line = _fails(capfd, ["export", run, "--format", "moodle", "--out", tmp_path / "q.xml"])
    assert "task.svg" in line and not (tmp_path / "q.xml").exists()


#: input → (the limit it is read up to, the argv, the file's suffix)
LIMITS: dict[str, tuple[int, list[str], str]] = {
    "exercise": (1_000_000, INPUTS["exercise (solve)"], ".toml"),
    "roster": (20_000_000, INPUTS["roster (variants)"], ".csv"),
    "coordinates": (50_000_000, INPUTS["coordinates (check)"], ".csv"),
    "key": (1_000_000_000, INPUTS["key (grade)"], ".json"),
}


@pytest.mark.parametrize("case", list(LIMITS))
def test_a_file_above_its_limit_is_refused_before_reading(capfd, tmp_path, case):
    """A sparse file one byte over the limit (no disk used): refused by its size."""
    limit, argv, suffix = LIMITS[case]
    path = tmp_path / f"big{suffix}"
    with path.open("wb") as handle:
        handle.truncate(limit + 1)
    line = _fails(capfd, _input_argv(argv, path, tmp_path))
    assert str(path) in line and f"at most {limit} are accepted" in line


def test_the_reader_reads_no_more_than_the_limit(tmp_path):
    """A file that the stat calls small but that reads longer (as /proc files do) is cut
    off at limit + 1 bytes and refused."""
    status = Path("/proc/self/status")
    if not status.exists() or os.stat(status).st_size:
        pytest.skip("needs a /proc file whose size is reported as 0")
    with pytest.raises(PlanmethodError, match="more than 10 bytes"):
        read_bytes_bounded(status, limit=10)
    assert len(read_bytes_bounded(status, limit=1_000_000)) > 10


# ---------------------------------------------------------------------------------------------
# a write that fails names the output it was writing, never the command's input (issue 35)

#: command → (argv with OUT for the output's folder, the output the error names, relative to
#: it); every command that writes, and each way a file is written: a text set (JSON, TOML,
#: HTML, XML, SVG files), a CSV streamed row by row, matplotlib's savefig, Pillow's GIF, a
#: folder staged whole (variants, export)
WRITERS: dict[str, tuple[list[str], str]] = {
    "sweep --csv": (["sweep", GOOD, "--step", "1", "--csv", "OUT/s.csv"], "s.csv"),
    "sweep --plot": (["sweep", GOOD, "--step", "30", "--plot", "OUT/s.png"], "s.png"),
    "study --plot": (["study", STUDY, "--step", "90", "--plot", "OUT/st.png"], "st.png"),
    "grade --report": (["grade", GOOD, "ANSWERS", "--report", "OUT/report"],
                       "report/class_report.png"),
    "grade --json": (["grade", GOOD, "ANSWERS", "--json", "OUT/g.json"], "g.json"),
    "solve --svg": (["solve", GOOD, "--svg", "OUT/svg"], "svg/position.svg"),
    "convert": (["convert", GOOD, "-o", "OUT/drawn.toml"], "drawn.toml"),
    "workbook": (["workbook", GOOD, "-o", "OUT/w.html", "--step", "90"], "w.html"),
    "animate": (["animate", GOOD, "-o", "OUT/turn.gif", "--step", "90"], "turn.gif"),
    "variants": (["variants", TEMPLATE, "--out", "OUT/run", "--count", "2"], "run/"),
    "export moodle": (["export", GOOD, "--format", "moodle", "--out", "OUT/q.xml"], "q.xml"),
    "export prairielearn": (["export", GOOD, "--format", "prairielearn", "--out", "OUT/pl"],
                            "pl/planmethod/"),
}


@pytest.mark.parametrize("case", list(WRITERS))
def test_a_write_that_fails_names_the_output(tmp_path, case):
    """A real process whose files may not exceed 1 kB (RLIMIT_FSIZE, as a full disk): one
    line naming the output (for a folder, a file in it) with the system's reason, exit 2,
    never the exercise; and nothing is left of the outputs."""
    import resource

    def small_files() -> None:
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)   # a write past the limit fails (EFBIG)
        resource.setrlimit(resource.RLIMIT_FSIZE, (1024, 1024))

    (tmp_path / "answers.csv").write_text("student,v_C,omega_BC\ns1,5,20\ns2,4,-24\n")
    argv, named = WRITERS[case]
    argv = [str(tmp_path / "answers.csv") if a == "ANSWERS" else a.replace("OUT", str(tmp_path))
            for a in argv]
    before = _tree(tmp_path)
    done = subprocess.run([sys.executable, "-m", "planmethod", *argv], capture_output=True,
                          text=True, cwd=ROOT, timeout=300, preexec_fn=small_files,
                          env={**os.environ, "PYTHONDONTWRITEBYTECODE": "1"})
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(lines) == 1, done.stderr[-2000:]
    assert lines[0].startswith(f"planmethod: error: {tmp_path / named}"), lines[0]
    assert "File too large" in lines[0] and GOOD not in lines[0]
    assert _tree(tmp_path) == before


def test_a_full_disk_while_the_csv_streams_names_the_csv(capfd, tmp_path, monkeypatch):
    """ENOSPC from the CSV's own file, mid-stream (a mocked full disk): the line names the
    CSV, not the exercise; neither the CSV nor the plot of the same run is left."""
    import errno
    import io
    import pathlib

    real_open = pathlib.Path.open

    class FullDisk(io.TextIOWrapper):
        def write(self, text: str) -> int:
            if self.tell() > 2000:
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
            return super().write(text)

    def opening(path, mode="r", *arguments, **keywords):
        handle = real_open(path, mode, *arguments, **keywords)
        if "w" in mode and path.name.startswith(".s.csv."):
            return FullDisk(handle.detach(), encoding="utf-8")
        return handle

    monkeypatch.setattr(pathlib.Path, "open", opening)
    line = _fails(capfd, ["sweep", GOOD, "--step", "1", "--csv", tmp_path / "s.csv",
                          "--plot", tmp_path / "s.png"])
    assert line == (f"planmethod: error: {tmp_path / 's.csv'}: cannot write the file: "
                    "No space left on device")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("case", ["a link that loops", "through a link that loops",
                                  "a file as its folder", "a name too long",
                                  "a folder name too long"])
def test_an_odd_output_path_is_one_line(capfd, tmp_path, case):
    (tmp_path / "loop").symlink_to("loop")
    (tmp_path / "file").write_text("mine")
    out = {"a link that loops": tmp_path / "loop",
           "a file as its folder": tmp_path / "file" / "s.csv",
           "through a link that loops": tmp_path / "loop" / "s.csv",
           "a name too long": tmp_path / ("x" * 300 + ".csv"),
           "a folder name too long": tmp_path / ("d" * 300) / "s.csv"}[case]
    before = _tree(tmp_path)
    line = _fails(capfd, ["sweep", GOOD, "--step", "90", "--csv", out])
    assert line.startswith(f"planmethod: error: {out}: ") and GOOD not in line
    assert _tree(tmp_path) == before


# ---------------------------------------------------------------------------------------------
# export folders: one run's files, as variants --force (issue 35)


def _export(run: Path, form: str, out: Path) -> list[str]:
    return ["export", str(run), "--format", form, "--out", str(out)]


@pytest.fixture
def two_runs(tmp_path, capfd) -> tuple[Path, Path]:
    """Two variants runs of different students: three, and two others from a roster."""
    three, two = tmp_path / "three", tmp_path / "two"
    (tmp_path / "roster.csv").write_text("student\nann\nbob\n")
    assert main(["variants", TEMPLATE, "--out", str(three), "--count", "3"]) == 0
    assert main(["variants", TEMPLATE, "--out", str(two), "--students",
                 str(tmp_path / "roster.csv")]) == 0
    capfd.readouterr()
    return three, two


@pytest.mark.parametrize(("form", "folder"), [("prairielearn", "planmethod"),
                                              ("gradescope", "")])
def test_a_second_export_leaves_exactly_its_own_files(tmp_path, capfd, two_runs, form, folder):
    """The folder holds afterwards exactly what the second export writes into an empty
    folder: not a task figure of a student of the first, byte for byte the same files, the
    autograder's scripts still executable; a question of another slug beside it stays."""
    three, two = two_runs
    out, fresh = tmp_path / "out", tmp_path / "fresh"
    (out / "another-question").mkdir(parents=True)
    (out / "another-question" / "info.json").write_text("{}")
    if form == "gradescope":
        out = out / "autograder"
    assert main(_export(three, form, out)) == 0
    first = _tree(out / folder)
    assert main(_export(two, form, out)) == 0
    assert main(_export(two, form, fresh)) == 0
    capfd.readouterr()
    assert _tree(out / folder) == _tree(fresh / folder) != first
    assert not any("003" in name for name in _tree(out / folder))
    assert (tmp_path / "out" / "another-question" / "info.json").read_text() == "{}"
    if form == "gradescope":
        assert os.access(out / "run_autograder", os.X_OK)
    else:
        assert sorted(os.listdir(out / folder / "clientFilesQuestion")) == [
            "task_1_ann.svg", "task_2_bob.svg"]


@pytest.mark.parametrize("case", ["a file it did not write", "an edited file", "no manifest",
                                  "a variants run"])
def test_an_export_never_empties_a_folder_of_other_files(tmp_path, capfd, two_runs, case):
    """Decided: a folder that holds anything the earlier export did not write (or changed
    since) is refused in one line naming it, and left exactly as it was — never wiped."""
    three, two = two_runs
    out = tmp_path / "autograder"
    assert main(_export(three, "gradescope", out)) == 0
    capfd.readouterr()
    if case == "a file it did not write":
        (out / "planmethod-src").mkdir()
    elif case == "an edited file":
        (out / "setup.sh").write_text("# mine\n")
    elif case == "no manifest":
        (out / "manifest.json").unlink()
    else:
        out = three
    before = _tree(tmp_path)
    line = _fails(capfd, _export(two, "gradescope", out))
    assert {"a file it did not write": "planmethod-src", "an edited file": "setup.sh changed",
            "no manifest": "holds no manifest.json",
            "a variants run": "not a manifest of export"}[case] in line
    assert _tree(tmp_path) == before


def test_a_single_file_export_is_replaced_whole(tmp_path, capfd, two_runs):
    """A quiz written over a longer earlier one holds nothing of it."""
    three, two = two_runs
    quiz, fresh = tmp_path / "quiz.xml", tmp_path / "fresh.xml"
    assert main(_export(three, "moodle", quiz)) == 0
    assert main(_export(two, "moodle", quiz)) == 0
    assert main(_export(two, "moodle", fresh)) == 0
    assert quiz.read_bytes() == fresh.read_bytes()
