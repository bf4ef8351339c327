"""What the master needs of a coupled subsystem, and its FMI 2.0 implementation on fmpy.

A `Subsystem` has real inputs and outputs by name, steps from t to t + h over inputs held or
following their first time derivatives (FMI's `fmi2SetRealInputDerivatives`), and, for the
implicit scheme, saves and restores its state (`fmi2GetFMUstate`/`fmi2SetFMUstate`). The
tests implement it in Python (linear oscillators); `FmuSubsystem` wraps an FMU.
"""

from __future__ import annotations

import fnmatch
import shutil
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np


class StepRefused(RuntimeError):
    """A subsystem refused a step (fmi2Discard/fmi2Error, or a non-finite output)."""


class FmuError(RuntimeError):
    """An FMU refused a call other than a step (a value, initialization, a state): the call,
    its arguments and the FMU's logged message, in one line."""


def _one_line(text: object) -> str:
    return " ".join(str(text).split())


class Subsystem:
    """The interface the master couples (all values SI, as the subsystem declares them)."""

    name: str = "subsystem"
    #: highest input derivative order the subsystem takes (0: inputs held over a step)
    input_derivative_order: int = 0
    #: saves and restores its state (needed by the implicit scheme)
    can_rollback: bool = False
    #: answers partial derivatives of outputs by inputs (`jacobian`)
    provides_jacobian: bool = False

    def names(self, causality: str) -> list[str]:
        """Variable names of a causality (`input`, `output`, `parameter`)."""
        raise NotImplementedError

    def get(self, names: list[str]) -> np.ndarray:
        raise NotImplementedError

    def set(self, names: list[str], values: Sequence[float] | np.ndarray) -> None:
        raise NotImplementedError

    def set_rates(self, names: list[str], rates: Sequence[float] | np.ndarray) -> None:
        """First time derivatives of inputs for the next step (only if
        `input_derivative_order >= 1`)."""
        raise NotImplementedError

    def step(self, t: float, h: float) -> None:
        """Advances from t to t + h; raises `StepRefused` with the subsystem's message."""
        raise NotImplementedError

    def save(self) -> Any:
        """The subsystem's state (an opaque handle for `restore`)."""
        raise NotImplementedError

    def restore(self, state: Any) -> None:
        raise NotImplementedError

    def free(self, state: Any) -> None:
        pass

    def enter_initialization(self, parameters: dict[str, float | str], start: float = 0.0) -> None:
        """Initialization mode with these start values (FMU subsystems)."""
        raise NotImplementedError

    def exit_initialization(self) -> None:
        raise NotImplementedError

    def reset(self) -> None:
        """Back to instantiated (FMU subsystems)."""
        raise NotImplementedError

    def jacobian(self, outputs: list[str], inputs: list[str]) -> np.ndarray:
        """∂outputs/∂inputs at the current point (direct feedthrough)."""
        raise NotImplementedError

    def close(self) -> None:
        pass


class FmuSubsystem(Subsystem):
    """An FMI 2.0 co-simulation FMU instance (fmpy), variables by name.

    Lifecycle: `instantiate()` → `enter_initialization(params)` → `exit_initialization()` →
    steps; `reset()` returns to instantiated. Every FMI status above fmi2Warning raises
    (`StepRefused` from `step`, `FmuError` from the other calls) with what the FMU logged
    during the call (its logger callback); a message the FMU logs with fmi2Warning goes to
    `on_warning(name, message)` when given.
    """

    def __init__(
        self, path: str, name: str, on_warning: Callable[[str, str], None] | None = None
    ) -> None:
        from fmpy import extract, read_model_description

        self.name = name
        self.path = str(path)
        self.md = read_model_description(self.path)
        if self.md.coSimulation is None:
            raise ValueError(f"{self.path}: not a co-simulation FMU (no <CoSimulation>)")
        cs = self.md.coSimulation
        self.dir = extract(self.path)
        self.vars = {v.name: v for v in self.md.modelVariables}
        self.vr = {n: v.valueReference for n, v in self.vars.items()}
        # FMI 2.0: canInterpolateInputs means the FMU takes first input derivatives
        self.input_derivative_order = 1 if cs.canInterpolateInputs else 0
        self.can_rollback = bool(cs.canGetAndSetFMUstate)
        self.provides_jacobian = bool(cs.providesDirectionalDerivative)
        self.messages: list[str] = []
        #: messages logged since the instance was made (the calls' marks)
        self.logged = 0
        self.on_warning = on_warning
        self.slave: Any = None

    def instantiate(self) -> None:
        from ctypes import byref

        from fmpy import calloc, free
        from fmpy.fmi2 import (
            FMU2Slave,
            fmi2CallbackAllocateMemoryTYPE,
            fmi2CallbackFreeMemoryTYPE,
            fmi2CallbackFunctions,
            fmi2CallbackLoggerTYPE,
        )

        def logger(env: Any, instance: Any, status: int, category: Any, message: bytes) -> None:
            text = _one_line(message.decode(errors="replace") if message else "")
            self.messages.append(text)
            self.logged += 1
            del self.messages[:-20]
            if status == 1 and self.on_warning is not None:  # fmi2Warning
                self.on_warning(self.name, text)

        # the FMU's messages (why a step or a call was refused) kept for the errors raised
        cb = fmi2CallbackFunctions()
        cb.logger = fmi2CallbackLoggerTYPE(logger)
        cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        try:
            from fmpy.logging import addLoggerProxy

            addLoggerProxy(byref(cb))  # formats the variadic message (fmpy's own proxy)
        except Exception:
            pass
        self._callbacks = cb
        try:
            self.slave = FMU2Slave(
                guid=self.md.guid,
                unzipDirectory=self.dir,
                modelIdentifier=self.md.coSimulation.modelIdentifier,
                instanceName=self.name,
            )
        except Exception as e:  # no binary for this platform, a library that does not load
            raise FmuError(
                f"{self.name} ({self.path}): cannot load its binary ({_one_line(e)}); build "
                "the FMU for this platform"
            ) from None
        self._call("fmi2Instantiate", self.slave.instantiate, callbacks=cb, loggingOn=False)

    def last_message(self) -> str:
        return self.messages[-1] if self.messages else ""

    def _call(self, what: str, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
        """`fn(*args)`, an FMI call; on a status above fmi2Warning (fmpy raises) an
        FmuError naming `what` with the FMU's messages logged during the call."""
        mark = self.logged
        try:
            return fn(*args, **kwargs)
        except Exception as e:
            k = min(self.logged - mark, len(self.messages))
            new = self.messages[len(self.messages) - k :]
            said = "; ".join(m for m in new if m) or _one_line(e)
            raise FmuError(f"{self.name}: {what} refused: {said}") from None

    def names(self, causality: str) -> list[str]:
        return [n for n, v in self.vars.items() if v.causality == causality]

    def match(self, pattern: str) -> list[str]:
        """Variable names matching a glob pattern (`*.density`)."""
        return [n for n in self.vars if fnmatch.fnmatchcase(n, pattern)]

    def parameters(self, pattern: str) -> list[str]:
        """The parameters among `match(pattern)`."""
        return [n for n in self.match(pattern) if self.vars[n].causality == "parameter"]

    def _vrs(self, names: Sequence[str]) -> list[int]:
        try:
            return [self.vr[n] for n in names]
        except KeyError as e:
            raise KeyError(f"{self.name} ({self.path}) has no variable {e.args[0]!r}") from None

    def get(self, names: list[str]) -> np.ndarray:
        return np.array(self._call("fmi2GetReal", self.slave.getReal, self._vrs(names)), float)

    def set(self, names: list[str], values: Sequence[float] | np.ndarray) -> None:
        floats = [float(x) for x in values]
        what = "fmi2SetReal(" + ", ".join(
            f"{n} = {x:g}" for n, x in zip(names, floats, strict=True)
        )
        what = (what[:300] + " ...") if len(what) > 300 else what
        self._call(what + ")", self.slave.setReal, self._vrs(names), floats)

    def set_rates(self, names: list[str], rates: Sequence[float] | np.ndarray) -> None:
        self._call(
            "fmi2SetRealInputDerivatives",
            self.slave.setRealInputDerivatives,
            self._vrs(names),
            [1] * len(names),
            [float(x) for x in rates],
        )

    def enter_initialization(self, parameters: dict[str, float | str], start: float = 0.0) -> None:
        self._call("fmi2SetupExperiment", self.slave.setupExperiment, startTime=start)
        self._call("fmi2EnterInitializationMode", self.slave.enterInitializationMode)
        text = {n: v for n, v in parameters.items() if self.vars[n].type == "String"}
        reals = {n: v for n, v in parameters.items() if n not in text}
        if reals:
            self.set(list(reals), [float(v) for v in reals.values()])
        if text:
            what = "fmi2SetString(" + ", ".join(f"{n} = {v!r}" for n, v in text.items()) + ")"
            self._call(
                what, self.slave.setString, self._vrs(list(text)), [str(v) for v in text.values()]
            )

    def exit_initialization(self) -> None:
        self._call("fmi2ExitInitializationMode", self.slave.exitInitializationMode)

    def reset(self) -> None:
        self._call("fmi2Reset", self.slave.reset)

    def step(self, t: float, h: float) -> None:
        try:
            status = self.slave.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        except Exception as e:  # fmpy raises on a status above fmi2Warning
            raise StepRefused(
                f"{self.name} refused the step at t = {t:.6g} s: {self.last_message() or e}"
            ) from None
        if status is not None and status > 1:
            raise StepRefused(
                f"{self.name} refused the step at t = {t:.6g} s: "
                f"{self.last_message() or f'fmi2Status {status}'}"
            )

    def save(self) -> Any:
        return self._call("fmi2GetFMUstate", self.slave.getFMUState)

    def restore(self, state: Any) -> None:
        self._call("fmi2SetFMUstate", self.slave.setFMUState, state)

    def free(self, state: Any) -> None:
        self.slave.freeFMUState(state)

    def jacobian(self, outputs: list[str], inputs: list[str]) -> np.ndarray:
        vo, vi = self._vrs(outputs), self._vrs(inputs)
        cols = []
        for k in range(len(inputs)):
            seed = [0.0] * len(inputs)
            seed[k] = 1.0
            cols.append(self.slave.getDirectionalDerivative(vo, vi, seed))
        return np.array(cols, dtype=float).T

    def close(self) -> None:
        if self.slave is not None:
            try:
                self.slave.terminate()
            except Exception:
                pass
            self.slave.freeInstance()
            self.slave = None
        shutil.rmtree(self.dir, ignore_errors=True)
