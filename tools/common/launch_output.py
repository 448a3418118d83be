"""What `uampc launch` says at its end, read once for the Python tools (loop_profile, speed_targets).

The launcher's last line: 'uampc: 40 s of sim time in 9.6 s (4.17x real time), after a start of ...'.
Its numbers are C++ stream output of doubles, so a short fast run may print 9.8e-05 s."""
import re

NUMBER = r"([0-9.]+(?:e[+-]?[0-9]+)?)"
_SUMMARY = re.compile(r"of sim time in %s s \(%sx real time\)" % (NUMBER, NUMBER))


def real_time_factor(output):
    """(real-time factor, wall seconds of the loop) from a launch's output; ValueError without it."""
    m = _SUMMARY.search(output)
    if not m:
        raise ValueError("no 'x real time' line in the launch's output")
    return float(m.group(2)), float(m.group(1))
