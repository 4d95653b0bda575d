"""The table of hostile inputs (see ``_hostile_cases``)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from pathlib import Path
from typing import Any, Callable

from _hostile_cases import ROOT, Case, Ctx, listing, run, xtask

Eps = list[dict[str, Any]]
TINY_TOML = ROOT / "crates/vlnverse-generate/configs/generate/tiny.toml"


def evaluate(d: Path, out: Path, *extra: str, task: str = "fine", split: str = "test",
             agent: str = "forward") -> list[str]:
    return ["evaluate", "--dataset", str(d), "--task", task, "--split", split,
            "--agent", agent, "--setting", "lenient", "--no-render", "--threads", "1",
            "--out", str(out), *extra]


def bad_episode(name: str, spoil: Callable[[dict[str, Any]], None], expect: tuple[str, ...],
                task: str = "fine") -> Case:
    """An evaluation of a split whose last episode is spoilt: refused, no run folder made."""
    def cli(c: Ctx) -> list[str]:
        d = c.spoil(task, "test", lambda eps: spoil(eps[-1]))
        return evaluate(d, c.work / "out", task=task)
    return Case(f"episode_{name}", cli=cli, expect=expect, watch=lambda c: c.work / "out")


def spoilt_split(name: str, how: Callable[[Eps], None], expect: tuple[str, ...],
                 raw: Callable[[str], str] | None = None) -> Case:
    def cli(c: Ctx) -> list[str]:
        return evaluate(c.spoil("fine", "test", how, raw), c.work / "out")
    return Case(f"split_{name}", cli=cli, expect=expect, watch=lambda c: c.work / "out")


def set_(key: str, value: Any) -> Callable[[dict[str, Any]], None]:
    def f(e: dict[str, Any]) -> None:
        e[key] = value
    return f


def protocol(c: Ctx, text: str) -> str:
    p = c.work / "protocol.toml"
    p.write_text(f'setting = "lenient"\nrender = false\nplots = 0\n{text}\n')
    return str(p)


def eval_config(name: str, text: str, expect: tuple[str, ...],
                agent: str = "forward", extra: tuple[str, ...] = ()) -> Case:
    def cli(c: Ctx) -> list[str]:
        return evaluate(c.dataset(), c.work / "out", "--config", protocol(c, text), *extra,
                        agent=agent)
    return Case(f"protocol_{name}", cli=cli, expect=expect, watch=lambda c: c.work / "out")


def gen_config(name: str, edit: Callable[[str], str], expect: tuple[str, ...]) -> Case:
    def cli(c: Ctx) -> list[str]:
        cfg = c.work / "gen.toml"
        cfg.write_text(edit(TINY_TOML.read_text()))
        return ["generate", "--config", str(cfg), "--out", str(c.work / "out")]
    return Case(f"generate_{name}", cli=cli, expect=expect, watch=lambda c: c.work / "out")


def llm(text: str) -> Callable[[str], str]:
    return lambda t: (f'{t}\n[instructions.llm]\nbase_url = "http://127.0.0.1:9/v1"\n'
                      f'model = "m"\nframes = 0\n{text}\n')


def score(c: Ctx, out: Path, traj: str = '{"episode_id": 1, "positions": [[0,0,0]], '
          '"stopped": true}\n') -> list[str]:
    t = c.work / "traj.jsonl"
    t.write_text(traj)
    return ["score", "--dataset", str(c.dataset()), "--task", "fine", "--split", "test",
            "--trajectories", str(t), "--out", str(out)]


def folder_with(c: Ctx, name: str, files: dict[str, str]) -> Path:
    d = c.work / name
    d.mkdir(parents=True, exist_ok=True)
    for f, text in files.items():
        (d / f).write_text(text)
    return d


def py_env(kwargs: str, then: str = "") -> Callable[[Ctx], str]:
    return lambda c: (f"env = vlnverse.make_vec({str(c.dataset())!r}, 'fine', 'test', "
                      f"render=False, {kwargs})\n{then}")


PY_AGENT = """
class Forward:
    name = "forward"
    def reset(self):
        pass
    def act(self, obs, infos):
        import numpy as np
        return np.ones(len(obs["instruction"]), dtype=np.int64)
"""


def py_evaluate(out: str, spoil: bool = False) -> Callable[[Ctx], str]:
    def code(c: Ctx) -> str:
        d = c.spoil("fine", "test", lambda eps: eps[-1].update(start_position=[500, 0, 500])) \
            if spoil else c.dataset()
        o = d if out == "dataset" else c.work / out
        return (PY_AGENT + f"vlnverse.evaluate(Forward(), dataset={str(d)!r}, task='fine', "
                f"split='test', out={str(o)!r}, render=False, progress=False)")
    return code


# -- cases with their own check ----------------------------------------------------------


def kill_and_resume(c: Ctx, case: Case) -> tuple[str, str]:
    """An evaluation killed (SIGKILL) mid-run resumes to the end with nothing half-written."""
    out = c.work / "out"
    cmd = [*xtask(), *evaluate(c.dataset(), out, split="train")]
    p = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    time.sleep(1.5)
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    rc, text = run(cmd, case.timeout, ROOT)
    if rc is None:
        return "hang", text[-300:]
    if rc != 0:
        return ("crash" if rc == 101 or rc < 0 else "unclear"), text[-300:]
    left = [f for f in listing(out) or [] if ".tmp" in f]
    summary = json.loads((out / "summary.json").read_text())
    if left or summary.get("episodes") != 24:
        return "partial", f"left {left}, summary {summary.get('episodes')} episodes"
    return "clear", "resumed to 24 episodes, no temporary files"


def concurrent_evaluations(c: Ctx, case: Case) -> tuple[str, str]:
    """A second evaluation into a folder another one is writing is refused by the lock."""
    out = c.work / "out"
    cfg = protocol(c, "external_timeout_s = 30.0")
    first = [*xtask(), *evaluate(c.dataset(), out, "--config", cfg, "--agent-cmd", "sleep 60",
                                 agent="external")]
    p = subprocess.Popen(first, cwd=ROOT, stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        for _ in range(100):
            if (out / "run.json").exists():
                break
            time.sleep(0.1)
        before = listing(out)
        rc, text = run([*xtask(), *evaluate(c.dataset(), out)], case.timeout, ROOT)
        after = listing(out)
    finally:
        os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    from _hostile_cases import classify
    return classify(case, rc, text, before, after), text.strip()[-300:]


def edited_split_resume(c: Ctx, case: Case) -> tuple[str, str]:
    """A resume after the goal of an episode the run finished moved is refused, naming
    episode_fingerprint."""
    out = c.work / "out"
    d = c.dataset()
    rc, text = run([*xtask(), *evaluate(d, out, "--episodes", "1")], case.timeout, ROOT)
    if rc != 0:
        return "unclear", f"the first run failed: {text[-300:]}"

    def move(eps: Eps) -> None:
        eps[0]["goals"] = eps[1]["goals"]
    c.spoil("fine", "test", move)
    before = listing(out)
    rc, text = run([*xtask(), *evaluate(d, out)], case.timeout, ROOT)
    from _hostile_cases import classify
    return classify(case, rc, text, before, listing(out)), text.strip()[-300:]


def resume_past_an_edited_unrun_episode(c: Ctx, case: Case) -> tuple[str, str]:
    """Editing an episode the run has not reached is no reason to refuse the resume: it runs
    the episode as it is now."""
    out = c.work / "out"
    d = c.dataset()
    rc, text = run([*xtask(), *evaluate(d, out, "--episodes", "1")], case.timeout, ROOT)
    if rc != 0:
        return "unclear", f"the first run failed: {text[-300:]}"

    def move(eps: Eps) -> None:
        eps[2]["goals"] = eps[1]["goals"]
    c.spoil("fine", "test", move)
    rc, text = run([*xtask(), *evaluate(d, out, "--episodes", "3")], case.timeout, ROOT)
    if rc is None:
        return "hang", text[-300:]
    if rc != 0:
        return ("crash" if rc == 101 or rc < 0 else "unclear"), text.strip()[-300:]
    summary = json.loads((out / "summary.json").read_text())
    if summary.get("episodes") != 3:
        return "partial", f"summary of {summary.get('episodes')} episodes, not 3"
    return "clear", "resumed to 3 episodes"


def _first_scene(c: Ctx) -> str:
    return str(sorted((c.tiny / "scenes").iterdir())[0])


def _first_start(c: Ctx) -> tuple[str, str]:
    """The scene folder and start position of the tiny dataset's first test episode."""
    import gzip
    eps = json.loads(gzip.decompress((c.tiny / "fine/test/test.json.gz").read_bytes()))
    ep = eps["episodes"][0]
    return str(c.tiny / "scenes" / ep["scene_id"]), ",".join(str(v) for v in ep["start_position"])


def render_rig(name: str, sensor: str, expect: tuple[str, ...]) -> Case:
    """`render` with a rig of one bad sensor: refused before any image is made."""
    def cli(c: Ctx) -> list[str]:
        rig = c.work / "rig.toml"
        rig.write_text(f"[[sensors]]\n{sensor}\n")
        scene, start = _first_start(c)
        return ["render", "--scene", scene, "--position", start, "--sensors", str(rig),
                "--out", str(c.work / "out")]
    return Case(f"rig_{name}", cli=cli, expect=expect, watch=lambda c: c.work / "out")


def agent_profile(name: str, line: str, expect: tuple[str, ...]) -> Case:
    """An evaluation whose agent profile file has one value out of range."""
    def cli(c: Ctx) -> list[str]:
        base = (ROOT / "crates/vlnverse-sim/configs/agent/vlnverse.toml").read_text()
        key = line.split("=")[0].strip()
        kept = [ln for ln in base.splitlines() if ln.split("=")[0].strip() != key]
        (c.work / "robot.toml").write_text(line + "\n" + "\n".join(kept) + "\n")
        return evaluate(c.dataset(), c.work / "out", "--config",
                        protocol(c, f'agent_profile = "{c.work / "robot.toml"}"'))
    return Case(f"agent_profile_{name}", cli=cli, expect=expect, watch=lambda c: c.work / "out")


def import_mapping(name: str, rule: str, expect: tuple[str, ...]) -> Case:
    """`import` of a one-triangle OBJ with a mapping rule out of range."""
    def cli(c: Ctx) -> list[str]:
        obj = c.work / "room.obj"
        obj.write_text("o Bed_1\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n")
        (c.work / "map.toml").write_text(f'[[rule]]\npattern = "Bed"\nclass = "bed"\n{rule}\n')
        return ["import", "--input", str(obj), "--mapping", str(c.work / "map.toml"),
                "--out", str(c.work / "out")]
    return Case(f"import_{name}", cli=cli, expect=expect, watch=lambda c: c.work / "out")


def deaf_external_agent(c: Ctx) -> list[str]:
    """An external agent that sleeps without reading, sent observations larger than the pipe
    buffer (a 192x192 RGB image in base64 is about 150 KB)."""
    (c.work / "big.toml").write_text(
        'backend = "raycast"\n[[sensors]]\ntype = "rgb"\nwidth = 192\nheight = 192\n')
    cfg = c.work / "protocol.toml"
    cfg.write_text('setting = "lenient"\nplots = 0\nrig = "big.toml"\n'
                   'external_observations = "base64"\nexternal_timeout_s = 1.0\n')
    return ["evaluate", "--dataset", str(c.dataset()), "--task", "fine", "--split", "test",
            "--agent", "external", "--agent-cmd", "exec sleep 60", "--setting", "lenient",
            "--config", str(cfg),
            "--episodes", "1", "--threads", "1", "--out", str(c.work / "out")]


def web_over_the_connection_limit(c: Ctx, case: Case) -> tuple[str, str]:
    """`serve` with its 256 connections held by clients that sent half a header: one more
    gets a 503 JSON error at once instead of waiting in the listen queue."""
    import socket
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    cmd = [*xtask(), "serve", "--dataset", str(c.dataset()), "--port", str(port),
           "--out", str(c.work / "web")]
    p = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    held: list[socket.socket] = []
    try:
        for _ in range(300):
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                time.sleep(0.1)
        for _ in range(256):
            h = socket.create_connection(("127.0.0.1", port), timeout=5)
            h.sendall(f"GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n".encode())
            held.append(h)
        extra = socket.create_connection(("127.0.0.1", port), timeout=5)
        extra.sendall(f"GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                      "Connection: close\r\n\r\n".encode())
        answer = b""
        try:
            while chunk := extra.recv(65536):
                answer += chunk
        except socket.timeout:
            return "hang", f"no answer within 5 s ({len(answer)} bytes)"
        extra.close()
    finally:
        for h in held:
            h.close()
        os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    text = answer.decode(errors="replace")
    head, _, body = text.partition("\r\n\r\n")
    if not head.startswith("HTTP/1.1 503"):
        return "unclear", text[:300]
    try:
        message = json.loads(body)["error"]
    except (ValueError, KeyError):
        return "unclear", f"not the JSON error shape: {body[:300]}"
    outcome = "clear" if all(w in message for w in case.expect) else "unclear"
    return outcome, f"503 {message}"


def llm_made_up_object(c: Ctx, case: Case) -> tuple[str, str]:
    """Generation with an LLM stage whose every rewrite names a spaceship, verifier off and
    on_reject = "error": the rewrite check stops the run naming the word."""
    import http.server
    import threading

    class Stub(http.server.BaseHTTPRequestHandler):
        def do_POST(self) -> None:  # noqa: N802 (the http.server name)
            self.rfile.read(int(self.headers.get("Content-Length", 0)))
            body = json.dumps({"choices": [{"message": {
                "content": "Walk past the spaceship and stop by the door."}}]}).encode()
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, *args: Any) -> None:
            pass

    srv = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Stub)
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    try:
        url = f"http://127.0.0.1:{srv.server_address[1]}/v1"
        cfg = c.work / "gen.toml"
        # The reply cache outside --out: kept on purpose (a rerun pays nothing twice).
        cache = f'cache_dir = "{c.work / "cache"}"'
        cfg.write_text(llm(f'verify = false\non_reject = "error"\n{cache}')(TINY_TOML.read_text())
                       .replace("http://127.0.0.1:9/v1", url))
        out = c.work / "out"
        rc, text = run([*xtask(), "generate", "--config", str(cfg), "--out", str(out)],
                       case.timeout, ROOT)
    finally:
        srv.shutdown()
    from _hostile_cases import classify
    return classify(case, rc, text, None, listing(out)), text.strip()[-300:]


CASES: list[Case] = [
    # Episodes that cannot be right, each the last of its split.
    bad_episode("empty_instruction",
                lambda e: e["instruction"].update(instruction_text=""), ("instruction_text",)),
    bad_episode("negative_geodesic",
                lambda e: e["info"].update(geodesic_distance=-5), ("geodesic_distance", "-5")),
    bad_episode("empty_reference_path", set_("reference_path", []), ("reference_path",)),
    bad_episode("zero_rotation", set_("start_rotation", [0, 0, 0, 0]), ("start_rotation",)),
    bad_episode("long_rotation", set_("start_rotation", [0, 0, 0, 2]), ("start_rotation",)),
    bad_episode("tilted_rotation", set_("start_rotation", [0.5, 0, 0, 0.866]),
                ("start_rotation",)),
    bad_episode("negative_radius", lambda e: e["goals"][0].update(radius=-1), ("radius", "-1")),
    bad_episode("no_goals", set_("goals", []), ("goals",)),
    bad_episode("other_task", set_("task", "coarse"), ("task", "coarse")),
    bad_episode("long_horizon_without_sub_goals", set_("sub_goals", []), ("sub_goals",),
                task="long_horizon"),
    bad_episode("unknown_target_object", set_("target_object_id", 999999),
                ("target_object_id", "999999"), task="coarse"),
    bad_episode("start_off_the_map", set_("start_position", [500.0, 0.0, 500.0]),
                ("start_position", "navigable map")),
    bad_episode("goal_off_the_map", lambda e: e["goals"][0].update(position=[-500, 0, 3]),
                ("goals", "navigable map")),
    bad_episode("start_in_the_air", lambda e: e["start_position"].__setitem__(1, 5.0),
                ("start_position", "floor")),
    bad_episode("scene_outside_the_dataset", set_("scene_id", "../../etc"), ("scene_id",)),
    bad_episode("absolute_scene", set_("scene_id", "/etc"), ("scene_id",)),
    bad_episode("missing_scene", set_("scene_id", "no_such_home"), ("scene_id", "no_such_home")),
    bad_episode("string_episode_id", set_("episode_id", "seven"), ("episode_id",)),
    # Split files.
    spoilt_split("repeated_id", lambda eps: eps[-1].update(episode_id=eps[0]["episode_id"]),
                 ("used twice",)),
    spoilt_split("empty", lambda eps: eps.clear(), ("no episodes",)),
    spoilt_split("nan_in_gzip", lambda eps: None, ("nan", "geodesic_distance"),
                 raw=lambda t: t.replace('"geodesic_distance": ', '"geodesic_distance": NaN, '
                                         '"x": ', 1)),
    Case("split_not_gzip", expect=("not gzip",), watch=lambda c: c.work / "out",
         cli=lambda c: (
             (c.dataset() / "fine/test/test.json.gz").write_text("hello"),
             evaluate(c.dataset(), c.work / "out"))[1]),
    # Command-line values.
    Case("evaluate_threads_100000", expect=("threads", "100000"), watch=lambda c: c.work / "out",
         cli=lambda c: [*evaluate(c.dataset(), c.work / "out")[:-4], "--threads", "100000",
                        "--out", str(c.work / "out")]),
    Case("evaluate_episodes_0", expect=("episodes",), watch=lambda c: c.work / "out",
         cli=lambda c: evaluate(c.dataset(), c.work / "out", "--episodes", "0")),
    Case("evaluate_unknown_agent", expect=("agent", "nobody"), watch=lambda c: c.work / "out",
         cli=lambda c: evaluate(c.dataset(), c.work / "out", agent="nobody")),
    Case("evaluate_out_is_the_dataset", expect=("dataset folder",), watch=lambda c: c.dataset(),
         cli=lambda c: evaluate(c.dataset(), c.dataset())),
    Case("evaluate_out_is_a_file", expect=("is a file",), watch=lambda c: c.work / "f",
         setup=lambda c: (c.work / "f").write_text("x"),
         cli=lambda c: evaluate(c.dataset(), c.work / "f")),
    Case("export_threads_100000", expect=("threads", "100000"), watch=lambda c: c.work / "out",
         cli=lambda c: ["export", "--dataset", str(c.dataset()), "--task", "fine", "--split",
                        "test", "--threads", "100000", "--out", str(c.work / "out")]),
    Case("export_impossible_episode", expect=("start_position",),
         watch=lambda c: c.work / "out",
         cli=lambda c: ["export", "--dataset", str(c.spoil(
             "fine", "test", lambda eps: eps[-1].update(start_position=[500, 0, 500]))),
             "--task", "fine", "--split", "test", "--out", str(c.work / "out")]),
    Case("render_top_down_0", expect=("--top-down 0",), watch=lambda c: c.work / "out",
         cli=lambda c: ["render", "--scene", _first_scene(c), "--top-down", "0",
                        "--out", str(c.work / "out")]),
    # Protocol files.
    eval_config("success_distance_nan", "success_distance = nan", ("success_distance",)),
    eval_config("max_steps_0", "max_steps = 0", ("max_steps",)),
    eval_config("external_timeout_huge", "external_timeout_s = 1e12", ("external_timeout_s",)),
    eval_config("unknown_key", "speed = 3", ("speed",)),
    eval_config("external_agent_never_replies", "external_timeout_s = 1.0",
                ("no reply within", "cat > /dev/null", "step 0"), agent="external",
                extra=("--agent-cmd", "cat > /dev/null")),
    eval_config("external_agent_exits", "",
                ("exit status: 3",), agent="external", extra=("--agent-cmd", "exit 3")),
    # Generation configs.
    gen_config("a_billion_episodes",
               lambda t: t.replace("episodes = { train = 24,", "episodes = { train = 1000000000,"),
               ("episodes", "1000000000")),
    gen_config("max_attempts_0", lambda t: t.replace("max_attempts = 400", "max_attempts = 0"),
               ("max_attempts",)),
    gen_config("max_length_1e30", lambda t: t.replace("max_length = 20.0", "max_length = 1e30", 1),
               ("max_length",)),
    gen_config("camera_height_nan", lambda t: t.replace("camera_height = 1.25",
                                                        "camera_height = nan"),
               ("camera_height",)),
    gen_config("llm_timeout_1e20", llm("timeout_s = 1e20"), ("timeout_s",)),
    gen_config("llm_retries_1e9", llm("retries = 1000000000\nretry_backoff_ms = 1000000000000000"),
               ("retries",)),
    gen_config("llm_base_url_broken", lambda t: llm("")(t).replace(
        "http://127.0.0.1:9/v1", "http://[::1"), ("base_url",)),
    gen_config("llm_key_variable_unset", llm('api_key_env = "VLNVERSE_HOSTILE_UNSET_KEY"'),
               ("api_key_env", "VLNVERSE_HOSTILE_UNSET_KEY")),
    Case("generate_llm_cache_unwritable", expect=("cache_dir",), watch=lambda c: c.work / "out",
         setup=lambda c: (c.work / "file").write_text("x"),
         cli=lambda c: ((c.work / "gen.toml").write_text(
             llm(f'cache_dir = "{c.work / "file" / "cache"}"')(TINY_TOML.read_text())),
             ["generate", "--config", str(c.work / "gen.toml"), "--out",
              str(c.work / "out")])[1]),
    # Scoring.
    Case("score_into_a_finished_evaluation", expect=("evaluation", "run.json"),
         watch=lambda c: c.work / "eval",
         setup=lambda c: folder_with(c, "eval", {"run.json": "{}", "trajectories.jsonl": ""}),
         cli=lambda c: score(c, c.work / "eval")),
    Case("score_over_another_summary", expect=("summary.json", "--force"),
         watch=lambda c: c.work / "other",
         setup=lambda c: folder_with(c, "other", {"summary.json": "{}"}),
         cli=lambda c: score(c, c.work / "other")),
    Case("score_into_the_dataset", expect=("dataset folder",), watch=lambda c: c.dataset(),
         cli=lambda c: score(c, c.dataset())),
    Case("score_nan_trajectory", expect=("nan", "line 1"), watch=lambda c: c.work / "out",
         cli=lambda c: score(c, c.work / "out", '{"episode_id": 1, "positions": [[NaN,0,0]], '
                                                '"stopped": true}\n')),
    Case("score_unknown_episode", expect=("99999",), watch=lambda c: c.work / "out",
         cli=lambda c: score(c, c.work / "out", '{"episode_id": 99999, "positions": '
                                                '[[0,0,0]], "stopped": true}\n')),
    Case("score_success_distance_nan", expect=("success_distance",),
         watch=lambda c: c.work / "out",
         cli=lambda c: [*score(c, c.work / "out"), "--success-distance", "nan"]),
    Case("score_negative_start_tolerance", expect=("start_tolerance",),
         watch=lambda c: c.work / "out",
         cli=lambda c: [*score(c, c.work / "out"), "--start-tolerance=-1"]),
    Case("score_empty_trajectory_file", expect=("no trajectories",),
         watch=lambda c: c.work / "out", cli=lambda c: score(c, c.work / "out", "")),
    Case("score_missing_trajectory_file", expect=("nope.jsonl",),
         watch=lambda c: c.work / "out",
         cli=lambda c: [*score(c, c.work / "out")[:-4], "--trajectories",
                        str(c.work / "nope.jsonl"), "--out", str(c.work / "out")]),
    # More command-line values.
    Case("evaluate_sample_0", expect=("sample",), watch=lambda c: c.work / "out",
         cli=lambda c: evaluate(c.dataset(), c.work / "out", "--sample", "0")),
    Case("evaluate_missing_dataset", expect=("nope",), watch=lambda c: c.work / "out",
         cli=lambda c: evaluate(c.work / "nope", c.work / "out")),
    Case("evaluate_missing_config", expect=("nope.toml",), watch=lambda c: c.work / "out",
         cli=lambda c: evaluate(c.dataset(), c.work / "out", "--config",
                                str(c.work / "nope.toml"))),
    Case("evaluate_unknown_backend", expect=("backend", "bogus"),
         watch=lambda c: c.work / "out",
         cli=lambda c: evaluate(c.dataset(), c.work / "out", "--backend", "bogus")),
    eval_config("missing_rig", 'rig = "nope_rig.toml"', ("nope_rig.toml",)),
    eval_config("unknown_profile", 'agent_profile = "robot9"', ("robot9",)),
    eval_config("plots_huge", "plots = 1000000", ("plots",)),
    Case("export_episodes_0", expect=("episodes",), watch=lambda c: c.work / "out",
         cli=lambda c: ["export", "--dataset", str(c.dataset()), "--task", "fine", "--split",
                        "test", "--episodes", "0", "--out", str(c.work / "out")]),
    Case("export_out_is_a_file", expect=("file",), watch=lambda c: c.work / "f",
         setup=lambda c: (c.work / "f").write_text("x"),
         cli=lambda c: ["export", "--dataset", str(c.dataset()), "--task", "fine", "--split",
                        "test", "--episodes", "1", "--out", str(c.work / "f")]),
    Case("render_position_nan", expect=("--position",), watch=lambda c: c.work / "out",
         cli=lambda c: ["render", "--scene", _first_scene(c), "--position", "nan,0,0",
                        "--out", str(c.work / "out")]),
    Case("render_missing_scene", expect=("no_scene",), watch=lambda c: c.work / "out",
         cli=lambda c: ["render", "--scene", str(c.work / "no_scene"), "--position", "0,0,0",
                        "--out", str(c.work / "out")]),
    gen_config("a_billion_scenes", lambda t: t.replace("train = 3\n", "train = 1000000000\n", 1),
               ("splits",)),
    gen_config("llm_on_reject_maybe", llm('on_reject = "maybe"'), ("on_reject", "maybe")),
    gen_config("llm_frames_100", llm("frames = 100"), ("frames",)),
    gen_config("llm_temperature_nan", llm("temperature = nan"), ("temperature",)),
    Case("generate_out_is_a_file", expect=("file",), watch=lambda c: c.work / "f",
         setup=lambda c: (c.work / "f").write_text("x"),
         cli=lambda c: ["generate", "--preset", "tiny", "--out", str(c.work / "f")]),
    # Python calls.
    Case("python_unknown_task", expect=("task", "finest"),
         py=lambda c: f"vlnverse.make_vec({str(c.dataset())!r}, 'finest', 'test')"),
    Case("python_load_episodes_nan", expect=("nan",),
         py=lambda c: (c.spoil("fine", "test", lambda eps: None, raw=lambda t: t.replace(
             '"geodesic_distance": ', '"geodesic_distance": NaN, "x": ', 1)),
             f"vlnverse.load_episodes({str(c.dataset())!r}, 'fine', 'test')")[1]),
    Case("python_score_into_an_evaluation", expect=("evaluation",),
         watch=lambda c: c.work / "eval",
         setup=lambda c: folder_with(c, "eval", {"run.json": "{}", "trajectories.jsonl": ""}),
         py=lambda c: (score(c, c.work / "eval"),
                       f"vlnverse.score({str(c.dataset())!r}, 'fine', 'test', "
                       f"{str(c.work / 'traj.jsonl')!r}, {str(c.work / 'eval')!r})")[1]),
    Case("python_make_vec_4096", py=py_env("num_envs=4096"), expect=("num_envs", "4096")),
    Case("python_seed_2_70", py=py_env("seed=2**70"), expect=("seed",)),
    Case("python_max_steps_1e12", py=py_env("max_steps=10**12"), expect=("max_steps",)),
    Case("python_episode_ids_negative", py=py_env("episode_ids=[-1]"),
         expect=("episode_ids", "-1")),
    Case("python_episode_ids_repeated", py=py_env("episode_ids=[1, 1, 1]"),
         expect=("episode_ids", "repeats")),
    Case("python_profile_5", py=py_env("profile=5"), expect=("profile",)),
    Case("python_success_distance_text", py=py_env("success_distance='far'"),
         expect=("success_distance",)),
    Case("python_unknown_reset_option", py=py_env("", "env.reset(options={'teleport': 1})"),
         expect=("teleport",)),
    Case("python_evaluate_into_the_dataset", py=py_evaluate("dataset"),
         expect=("dataset folder",), watch=lambda c: c.dataset()),
    Case("python_evaluate_impossible_episode", py=py_evaluate("out", spoil=True),
         expect=("start_position",), watch=lambda c: c.work / "out"),
    # Kills and concurrent jobs.
    Case("kill_then_resume", custom=kill_and_resume, timeout=120),
    Case("two_evaluations_on_one_folder", custom=concurrent_evaluations,
         expect=("another job",)),
    Case("resume_of_an_edited_split", custom=edited_split_resume,
         expect=("episode_fingerprint", "--fresh")),
    Case("resume_past_an_edited_unrun_episode", custom=resume_past_an_edited_unrun_episode),
    # Sensor rigs, agent profiles and import mappings with values out of range.
    render_rig("width_1e6", 'type = "rgb"\nwidth = 1000000', ("sensors[0].width", "1000000")),
    render_rig("hfov_nan", 'type = "rgb"\nhfov_deg = nan', ("sensors[0].hfov_deg", "nan")),
    render_rig("hfov_0", 'type = "depth"\nhfov_deg = 0.0', ("sensors[0].hfov_deg",)),
    render_rig("far_1e9", 'type = "depth"\nfar = 1e9', ("sensors[0].far", "1000000000")),
    render_rig("redwood_c_nan", 'type = "depth"\nnoise = { model = "redwood", a = 0.001, '
               'b = 0.002, c = nan, quantum = 0.003 }', ("sensors[0].noise.c",)),
    render_rig("lidar_a_billion_rays", 'type = "lidar"\nbeams = 65536\nchannels = 1024',
               ("sensors[0].beams", "rays")),
    render_rig("panorama_360_big_views", 'type = "panorama"\nviews = 360\n'
               'camera = { width = 1024, height = 1024 }', ("sensors[0].views", "pixels")),
    agent_profile("step_size_1e6", "step_size = 1e6", ("robot.toml", "step_size", "1000000")),
    agent_profile("turn_angle_0", "turn_angle_deg = 0.0", ("robot.toml", "turn_angle_deg")),
    agent_profile("speed_nan", "max_linear_speed = nan", ("robot.toml", "max_linear_speed")),
    import_mapping("mass_1e12", "mass = 1e12", ("map.toml", "rule[0].mass")),
    import_mapping("friction_inf", "friction = inf", ("map.toml", "rule[0].friction")),
    # An external agent that never reads its input.
    Case("external_agent_never_reads", cli=deaf_external_agent,
         expect=("did not read", "exec sleep 60", "step 0", "external_timeout_s"),
         watch=lambda c: c.work / "out"),
    # The web app over its connection limit.
    Case("web_connection_over_the_limit", custom=web_over_the_connection_limit,
         expect=("busy", "256")),
    # An LLM rewrite naming an object the facts do not hold.
    Case("llm_rewrite_names_a_spaceship", custom=llm_made_up_object, timeout=120,
         expect=("spaceship", "on_reject")),
]
