"""FMUs that are only a modelDescription.xml (no binary): enough for the checks the tools make
against an FMU's variables before they instantiate it (names, causality, type)."""

import zipfile

_HEADER = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="{name}"
  guid="{{00000000-0000-0000-0000-000000000000}}"
  variableNamingConvention="structured" numberOfEventIndicators="0">
  <CoSimulation modelIdentifier="{name}" canGetAndSetFMUstate="true" canInterpolateInputs="true"/>
  <ModelVariables>
"""


def write_fmu(path, name: str, variables: dict[str, tuple[str, str]]):
    """Writes `path` (an FMU without binaries) declaring `variables`: name -> (causality,
    type), type Real or String; returns `path`."""
    lines, outputs = [], []
    for i, (v, (causality, kind)) in enumerate(variables.items(), start=1):
        var = f'causality="{causality}"'
        if causality == "parameter":
            var += ' variability="fixed"'
            start = ' start=""' if kind == "String" else ' start="1.0"'
        elif causality == "input":
            var += ' variability="continuous"'
            start = ' start="0.0"'
        else:
            var += ' variability="continuous"'
            start = ""
        lines.append(
            f'    <ScalarVariable name="{v}" valueReference="{i}" {var}><{kind}{start}/>'
            "</ScalarVariable>"
        )
        if causality == "output":
            outputs.append(f'      <Unknown index="{i}"/>')
    xml = (
        _HEADER.format(name=name)
        + "\n".join(lines)
        + "\n  </ModelVariables>\n  <ModelStructure>\n"
        + (("    <Outputs>\n" + "\n".join(outputs) + "\n    </Outputs>\n") if outputs else "")
        + "  </ModelStructure>\n</fmiModelDescription>\n"
    )
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("modelDescription.xml", xml)
    return path


#: the boom FMU's variables the tests use (scenes/boom.toml, docs/fmu-variables.md)
BEAM = {
    "tip.length": ("parameter", "Real"),
    "tip.density": ("parameter", "Real"),
    "root.density": ("parameter", "Real"),
    "tip.inner_diameter": ("parameter", "Real"),
    "root.inner_diameter": ("parameter", "Real"),
    "tip.youngs_modulus": ("parameter", "Real"),
    "root.youngs_modulus": ("parameter", "Real"),
    "visualization.directory": ("parameter", "String"),
    "tip.force.y": ("input", "Real"),
    "root.position.y": ("input", "Real"),
    "root.acceleration.y": ("input", "Real"),
    "tip.position.y": ("output", "Real"),
    "root.force.y": ("output", "Real"),
    "root.moment.z": ("output", "Real"),
    "energy.kinetic": ("output", "Real"),
}

#: a carrier (the car's side of the vehicle example)
CAR = {
    "mass": ("parameter", "Real"),
    "mount.position.y": ("output", "Real"),
    "mount.acceleration.y": ("output", "Real"),
    "beam.root.force.y": ("input", "Real"),
    "body.pitch": ("output", "Real"),
    "energy.total": ("output", "Real"),
}
