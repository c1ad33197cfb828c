# SPDX-License-Identifier: Apache-2.0
"""Testing diffraction kernels: the generic kernel contract suite from Python.

check_kernel(name, presets) runs on a registered kernel — written in Python (phasor.Material) or
in C++ — exactly the checks tests/materials/kernel_contract_test.cpp runs on every C++ kernel: χ²
of the sampled directions against Pdf, the pdf's normalisation, weight = eval·cos/pdf, importance
vs uniform estimates, the white furnace (energy ≤ 1), reciprocity, finiteness, the near-delta
lobes' listing, geometry and choice probabilities, the lobe mask, EvalLobe. Each case is one
preset × one of the suite's wavelengths (WAVELENGTHS) × one incident direction (INCIDENTS);
statistical tests use fixed seeds and a Šidák-corrected level of 1 % over the whole run.
"""

from . import _phasor
from ._errors import KernelContractError

#: The suite's wavelengths [m] and incident directions (cos θ, φ [rad]) in the local frame.
WAVELENGTHS, INCIDENTS = _phasor._contract_domain()
WAVELENGTHS = tuple(WAVELENGTHS)
INCIDENTS = tuple(tuple(i) for i in INCIDENTS)


class KernelReport:
    """What check_kernel found: ``passed`` (bool; also ``bool(report)``), ``outcomes`` (one dict
    per check and case: check, case, status "passed" | "failed" | "skipped", failures, messages,
    properties such as p-values), ``failures`` (the failed outcomes), ``checks`` ({check: {passed,
    failed, skipped}}), ``cases`` (their names: kernel_p<preset>_<λ>nm_in<incident>) and ``alpha``
    (the level each statistical test used). ``str(report)`` lists the failures with the suite's
    messages; raise_for_failures() raises KernelContractError (an AssertionError) with it."""

    def __init__(self, kernel, cases, outcomes, alpha):
        self.kernel = kernel
        self.cases = list(cases)
        self.outcomes = list(outcomes)
        self.alpha = alpha

    @property
    def failures(self):
        return [o for o in self.outcomes if o["status"] == "failed"]

    @property
    def passed(self):
        return bool(self.outcomes) and not self.failures

    def __bool__(self):
        return self.passed

    @property
    def checks(self):
        table = {}
        for o in self.outcomes:
            row = table.setdefault(o["check"], {"passed": 0, "failed": 0, "skipped": 0})
            row[o["status"]] += 1
        return table

    def failed_checks(self):
        """The names of the checks that failed in some case."""
        return sorted({o["check"] for o in self.failures})

    def __str__(self):
        head = (f"kernel contract of '{self.kernel}': "
                f"{'passed' if self.passed else 'FAILED'} — {len(self.cases)} cases × {len(self.checks)} checks, "
                f"{len(self.failures)} failed, alpha = {self.alpha:.3g}")
        lines = [head]
        for check, row in self.checks.items():
            lines.append(f"  {check}: {row['passed']} passed, {row['failed']} failed, {row['skipped']} skipped")
        shown = self.failures[:10]
        for o in shown:
            lines.append(f"  FAILED {o['check']} [{o['case']}] ({o['failures']} failure{'s' if o['failures'] != 1 else ''}):")
            lines.extend("    " + m.replace("\n", "\n    ") for m in o["messages"])
        if len(self.failures) > len(shown):
            lines.append(f"  … and {len(self.failures) - len(shown)} more failed outcomes")
        return "\n".join(lines)

    __repr__ = __str__

    def raise_for_failures(self):
        """Raises KernelContractError (an AssertionError, so pytest reports it as a failed
        assertion) with the report when a check failed."""
        if not self.passed:
            raise KernelContractError(str(self), self)


def _indices(values, domain, what, convert):
    if values is None:
        return []
    out = []
    for v in values:
        x = convert(v)
        match = [i for i, d in enumerate(domain) if abs(x - d) <= 1e-9 * abs(d)]
        if not match:
            raise ValueError(f"{what} {v!r} is not one of the suite's: {domain}")
        out.append(match[0])
    return out


def check_kernel(name, presets=None, *, wavelengths=None, incidents=None, sample_scale=1.0,
                 raise_on_failure=True):
    """Runs the generic kernel contract suite on the registered kernel ``name`` and returns its
    KernelReport; raises KernelContractError (an AssertionError carrying ``.report``) when a check
    fails, unless raise_on_failure=False.

    presets: the parameter sets to check, a list of dicts as the kernel's ``presets`` attribute
    (numbers in SI units); they replace the class's (Python kernels only: a C++ kernel's are its
    TestPresets()). wavelengths: a subset of WAVELENGTHS (metres or "550nm"); incidents: indices
    into INCIDENTS; both default to all. sample_scale < 1 shrinks the statistical tests' samples
    (to at least 1000 each) for a quicker, less powerful check: a kernel written in Python costs
    microseconds per call, and the whole suite calls it about 10⁶ times per case."""
    if presets is not None:
        _phasor._set_presets(name, list(presets))
    if not (0 < sample_scale <= 1):
        raise ValueError("sample_scale must lie in (0, 1]")
    lam = _indices(wavelengths, WAVELENGTHS, "wavelength", lambda v: _phasor.quantity(v, "length"))
    inc = _indices(incidents, range(len(INCIDENTS)), "incident", int)
    cases, outcomes, alpha = _phasor._check_kernel(name, lam, inc, float(sample_scale))
    report = KernelReport(name, cases, outcomes, alpha)
    if raise_on_failure:
        report.raise_for_failures()
    return report
