# SPDX-License-Identifier: BSD-3-Clause
"""The module under a comma-decimal LC_NUMERIC (de_DE): settings are read and
results written as in the C locale.

A Python program may call locale.setlocale(locale.LC_ALL, "") (matplotlib
users, GUI toolkits, anyone who wants localised output). With a German or
French environment the C library's strtod then stopped at the '.' of "0.9",
so level=0.9 was refused, and snprintf wrote "0,5" into CSV files. The runs
happen in a child interpreter, so that the locale cannot leak into other
tests; a comma-decimal locale is taken from the system, or made with
localedef in a temporary directory (LOCPATH), or the test is skipped saying
why.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

NAMES = ("de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8", "nl_NL.UTF-8", "it_IT.UTF-8", "ru_RU.UTF-8")

# Runs in the child: the same calls in the C locale and in the comma locale.
CHILD = r"""
import json, locale, sys
import stickslip

def runs():
    d = stickslip.diffusivity(excursions=256, scheme="resolvent", dt=1e-3, level=0.9, seed=3, threads=2)
    s = stickslip.sweep(noise=[1.5, 2.5], tau=[0.5], excursions=64, scheme="resolvent", dt=2e-3, threads=2)
    m = stickslip.moments(trajectories=64, scheme="resolvent", dt=1e-3, times="0.1:1:3", v0=0.25, threads=2)
    out = {"level": d.level, "d_csv": d.to_csv(), "s_csv": s.to_csv(), "m_csv": m.to_csv(),
           "d_json": d.to_json(), "m_table": m.to_table()}
    try:
        stickslip.diffusivity(excursions=256, dt="1,5e-3")
        out["comma_refused"] = False
    except stickslip.InvalidParameterError as e:
        out["comma_refused"] = True
        out["comma_message"] = str(e)
    return out

c = runs()
locale.setlocale(locale.LC_NUMERIC, sys.argv[1])
decimal_point = locale.localeconv()["decimal_point"]
probe = locale.format_string("%.1f", 0.5)
comma = runs()
print(json.dumps({"decimal_point": decimal_point, "probe": probe, "c": c, "comma": comma}))
"""


def comma_locale(workdir):
    """(name, environment) of a comma-decimal locale, or (None, reason)."""
    env = dict(os.environ)
    for name in NAMES:
        if _decimal_point(name, env) == ",":
            return name, env
    localedef = shutil.which("localedef")
    if localedef is None:
        return None, "no comma-decimal locale installed, and no localedef to make one"
    if not os.path.exists("/usr/share/i18n/locales/de_DE"):
        return None, "no comma-decimal locale installed, and no de_DE locale source for localedef"
    subprocess.run([localedef, "-i", "de_DE", "-f", "UTF-8", os.path.join(workdir, "de_DE.UTF-8")],
                   capture_output=True, timeout=120)
    env["LOCPATH"] = workdir
    for name in ("de_DE.UTF-8", "de_DE.utf8"):
        if _decimal_point(name, env) == ",":
            return name, env
    return None, "localedef could not make a de_DE.UTF-8 locale"


def _decimal_point(name, env):
    code = ("import locale, sys\n"
            "try:\n    locale.setlocale(locale.LC_NUMERIC, sys.argv[1])\nexcept locale.Error:\n    sys.exit(1)\n"
            "print(locale.localeconv()['decimal_point'])")
    p = subprocess.run([sys.executable, "-c", code, name], capture_output=True, text=True, env=env, timeout=60)
    return p.stdout.strip() if p.returncode == 0 else None


class CommaLocaleTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.workdir = tempfile.mkdtemp(prefix="stickslip_locale_")
        name, env_or_reason = comma_locale(cls.workdir)
        if name is None:
            shutil.rmtree(cls.workdir, ignore_errors=True)
            raise unittest.SkipTest(env_or_reason)
        p = subprocess.run([sys.executable, "-c", CHILD, name], capture_output=True, text=True, env=env_or_reason,
                           timeout=300)
        if p.returncode != 0:
            raise AssertionError(f"the runs under {name} failed:\n{p.stderr}")
        cls.out = json.loads(p.stdout)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.workdir, ignore_errors=True)

    def test_the_locale_is_in_effect(self):
        self.assertEqual(self.out["decimal_point"], ",")
        self.assertEqual(self.out["probe"], "0,5")

    def test_settings_are_read_with_a_decimal_point(self):
        # level=0.9 was refused: "level must be a number, got '0.9'".
        self.assertEqual(self.out["comma"]["level"], 0.9)

    def test_a_decimal_comma_is_still_refused(self):
        for run in ("c", "comma"):
            self.assertTrue(self.out[run]["comma_refused"], run)
            self.assertIn("dt", self.out[run]["comma_message"])

    def test_outputs_are_those_of_the_c_locale(self):
        c, comma = self.out["c"], self.out["comma"]
        for key in ("d_csv", "s_csv", "m_csv"):
            self.assertEqual(comma[key], c[key], key)
        wall_time = re.compile(r"[0-9.e+-]+ s on \d+ threads?")  # differs from run to run
        self.assertEqual(wall_time.sub("", comma["m_table"]), wall_time.sub("", c["m_table"]))
        a, b = json.loads(c["d_json"]), json.loads(comma["d_json"])
        a.pop("work", None)
        b.pop("work", None)
        self.assertEqual(a, b)

    def test_no_decimal_commas_in_csv(self):
        # A decimal comma would split a number into two cells.
        for key in ("d_csv", "s_csv", "m_csv"):
            rows = [ln for ln in self.out["comma"][key].splitlines() if not ln.startswith("#")]  # provenance
            header = rows[0].split(",")
            for line in rows[1:]:
                self.assertEqual(len(line.split(",")), len(header), f"{key}: {line}")


if __name__ == "__main__":
    unittest.main()
