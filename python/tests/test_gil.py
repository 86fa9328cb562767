"""Y9: run() releases the GIL: Python threads keep running while C++ steps."""
import threading
import time

import fdem
from conftest import example


def test_main_thread_runs_while_run_is_busy():
    sim = fdem.Simulation.from_toml(example("03_contact_slide"))
    # long enough to be seen: 40000 demo steps take about 0.8 s at 20 us per step on one core
    # (3000 steps, 0.06 s on a quiet machine, were too short to tell)
    steps = 40000
    worker = threading.Thread(target=lambda: sim.run(steps=steps))
    ticks = 0
    t0 = time.perf_counter()
    worker.start()
    while worker.is_alive():
        ticks += 1  # Python bytecode of the main thread: needs the GIL
        time.sleep(0.002)
    elapsed = time.perf_counter() - t0
    worker.join()
    assert sim.step_count == steps
    # with the GIL held by run(), the loop above would not run until run() returned: 1-2 ticks.
    # Not a rate: on a loaded 2-core machine (ctest -j2 beside it) a 2 ms sleep can take 10-50
    # ms, and the former bound (a quarter of the ideal rate) failed twice under load 12-17
    assert elapsed > 0.1, "run too short to tell"
    assert ticks >= 10, (ticks, elapsed)


def test_request_stop_from_another_thread():
    sim = fdem.Simulation.from_toml(example("03_contact_slide"))
    result = {}
    worker = threading.Thread(target=lambda: result.update(sim.run(until=10.0)))
    worker.start()
    time.sleep(0.2)
    sim.request_stop()
    worker.join(timeout=30)
    assert not worker.is_alive()
    assert result["status"] == "stopped"
    assert 0 < sim.step_count < sim.end_time / sim.dt


def test_ctrl_c_stops_the_run_and_raises_keyboard_interrupt():
    import os
    import signal

    sim = fdem.Simulation.from_toml(example("03_contact_slide"))
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.perf_counter()
    try:
        sim.run(until=10.0)  # about 2 million steps: minutes, unless Ctrl-C stops it
    except KeyboardInterrupt:
        pass
    else:
        raise AssertionError("run() returned without KeyboardInterrupt")
    finally:
        timer.cancel()
    assert time.perf_counter() - t0 < 10.0
    steps = sim.step_count
    assert 0 < steps < 10.0 / sim.dt
    sim.run(steps=10)  # the simulation is usable afterwards
    assert sim.step_count == steps + 10
