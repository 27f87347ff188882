"""The stability catalogue, Facet's side: every case of tests/stability/cases.py rendered by
vtkFacetRenderFilter does what the catalogue states (its messages, its measure) and passes
the checks every render must pass (checks.py). One test per case.

    test_catalogue.py [-v] [Catalogue | LargestImage | Report]

`Catalogue` holds every case but the 16384 × 16384 image, which `LargestImage` runs alone
(about 5 GiB); `Report` checks that docs/stability-report.md reports every case.
"""
import os
import re
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cases import CASES  # noqa: E402
from checks import problems, run_facet  # noqa: E402

LARGEST = "16384 × 16384 image"
REPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs",
                      "stability-report.md")


def case_test(case):
    def test(self):
        found = problems(case, run_facet(case))
        self.assertEqual(found, [], "%s: states “%s”, but:\n  %s"
                         % (case.name, case.behaviour, "\n  ".join(found)))
    test.__doc__ = case.name
    return test


class Catalogue(unittest.TestCase):
    pass


class LargestImage(unittest.TestCase):
    pass


for number, case in enumerate(CASES):
    slug = re.sub(r"\W+", "_", case.name.encode("ascii", "replace").decode()).strip("_")
    owner = LargestImage if case.name == LARGEST else Catalogue
    setattr(owner, "test_%02d_%s" % (number, slug), case_test(case))


class Report(unittest.TestCase):
    def test_the_committed_report_has_every_case(self):
        with open(REPORT, encoding="utf-8") as report:
            rows = {line.split("|")[1].strip() for line in report if line.startswith("| ")}
        for case in CASES:
            name = case.name + (" **(known defect)**" if case.defect else "")
            self.assertIn(name, rows, "docs/stability-report.md has no row for %r: run "
                                      "`make stability-report`" % case.name)


if __name__ == "__main__":
    unittest.main()
