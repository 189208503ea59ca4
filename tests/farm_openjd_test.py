#!/usr/bin/env python3
"""The render-farm template examples/farm/parallax-openjd.yaml run as a scheduler runs it.

Reads the Open Job Description template, checks its parameters, expands each step's parameter
space into tasks (the ranges, the product of the task parameters), resolves the {{Param.X}} and
{{Task.Param.X}} references, and runs every task's command with the real binary: the Render
tasks in reverse order (a farm runs them in any order, on any worker), then the Video step that
depends on them. The frames must be byte for byte those of one `parallax render` of the whole
turntable, and the Video step must render no frame again.

Usage: farm_openjd_test.py PARALLAX_BINARY SOURCE_DIR
"""
import itertools
import os
import re
import subprocess
import sys
import tempfile

import yaml

binary, source = sys.argv[1], sys.argv[2]
failures = []


def check(name, condition):
    if not condition:
        failures.append(name)
        print("FAIL: " + name, file=sys.stderr)


template = yaml.safe_load(open(os.path.join(source, "examples/farm/parallax-openjd.yaml")))
check("the 2023-09 job template schema", template["specificationVersion"] == "jobtemplate-2023-09")

work = tempfile.mkdtemp()
given = {
    "Parallax": binary,
    "Scene": os.path.join(source, "scenes/checker-box.json"),
    "Display": os.path.join(source, "tests/fixtures/displays/small-9-views.json"),
    "OutputDir": os.path.join(work, "farm"),
    "Turntable": "90",
    "Duration": "0.35",
    "Fps": "20",  # 7 frames
    "Spp": "4",
    "Chunks": "3",  # 2, 2 and 3 frames
}

# The job's parameters: every one defined, with a type; given values within their limits, the
# others from their defaults.
params = {}
for definition in template["parameterDefinitions"]:
    name, kind = definition["name"], definition["type"]
    check(name + " has a known type", kind in ("STRING", "PATH", "INT", "FLOAT"))
    value = given.get(name, definition.get("default"))
    check(name + " has a value", value is not None)
    if kind == "INT":
        number = int(value)
        check(name + " above its minimum", number >= definition.get("minValue", number))
        check(name + " below its maximum", number <= definition.get("maxValue", number))
    if kind == "FLOAT":
        float(value)
    params[name] = str(value)
check("every given parameter is defined", set(given) <= set(params))


def resolve(text, task):
    """A format string with its {{Param.X}} and {{Task.Param.X}} references replaced."""

    def value(match):
        reference = match.group(1).strip()
        if reference.startswith("Param."):
            return params[reference[len("Param."):]]
        if reference.startswith("Task.Param."):
            return task[reference[len("Task.Param."):]]
        raise ValueError("unknown reference " + reference)

    return re.sub(r"\{\{(.*?)\}\}", value, str(text))


def expand_range(definition):
    """A task parameter's values: a list, or an integer range expression "A-B[:STEP],..."."""
    values = definition["range"]
    if isinstance(values, list):
        return [resolve(v, {}) for v in values]
    out = []
    for part in resolve(values, {}).split(","):
        m = re.fullmatch(r"\s*(-?\d+)\s*(?:-\s*(-?\d+)\s*(?::\s*(\d+))?)?\s*", part)
        if not m:
            raise ValueError("not a range expression: " + part)
        first = int(m.group(1))
        last = int(m.group(2)) if m.group(2) else first
        step = int(m.group(3)) if m.group(3) else 1
        out += [str(v) for v in range(first, last + 1, step)]
    return out


def tasks(step):
    space = step.get("parameterSpace")
    if not space:
        return [{}]
    definitions = space["taskParameterDefinitions"]
    names = [d["name"] for d in definitions]
    return [dict(zip(names, combo)) for combo in itertools.product(*map(expand_range, definitions))]


def run(step, task):
    action = step["script"]["actions"]["onRun"]
    command = [resolve(action["command"], task)] + [resolve(a, task) for a in action.get("args", [])]
    done = subprocess.run(command, capture_output=True, text=True)
    check("%s %s exits 0 (%s)" % (step["name"], task, done.stderr.strip()), done.returncode == 0)
    return done.stdout


# The steps in an order that respects their dependencies.
steps = {s["name"]: s for s in template["steps"]}
order, seen = [], set()
while len(order) < len(steps):
    ready = [n for n, s in steps.items() if n not in seen and
             all(d["dependsOn"] in seen for d in s.get("dependencies", []))]
    check("the step dependencies have no cycle", ready)
    if not ready:
        break
    for n in ready:
        order.append(n)
        seen.add(n)
check("Render, then Video", order == ["Render", "Video"])

render_tasks = tasks(steps["Render"])
check("one task per chunk", [t["Chunk"] for t in render_tasks] == ["1", "2", "3"])
for task in reversed(render_tasks):
    run(steps["Render"], task)
video_out = run(steps["Video"], {})
check("the Video step renders nothing again", "0 to render" in video_out)
video = os.path.join(params["OutputDir"], "turntable.mp4")
check("the video is written", os.path.isfile(video) and os.path.getsize(video) > 0)

# One process renders the whole turntable: the same frames, byte for byte.
reference = os.path.join(work, "one")
subprocess.run([binary, "render", params["Scene"], "--display", params["Display"], "--spp",
                params["Spp"], "--turntable", params["Turntable"], "--duration",
                params["Duration"], "--fps", params["Fps"], "-o", reference],
               check=True, capture_output=True)
frames = sorted(f for f in os.listdir(reference) if f.startswith("frame-"))
check("seven frames", len(frames) == 7)
check("the farm made the same frames",
      frames == sorted(f for f in os.listdir(params["OutputDir"]) if f.startswith("frame-")))
for frame in frames:
    for layer in ("image.png", "mask.png"):
        a = open(os.path.join(reference, frame, layer), "rb").read()
        b = open(os.path.join(params["OutputDir"], frame, layer), "rb").read()
        check("%s/%s is one process's" % (frame, layer), a == b)

subprocess.run(["rm", "-rf", work])
print("%d failed" % len(failures))
sys.exit(1 if failures else 0)
