//! The seam between the FMI layer and a model: the FMI layer drives any [`CoSimModel`]
//! and knows nothing of beams.

/// FMI 2.0 causality of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    /// Fixed or tunable parameter, set before initialization.
    Parameter,
    /// Input, set by the host before each step.
    Input,
    /// Output, read by the host after each step.
    Output,
}

/// FMI 2.0 variability of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variability {
    /// Constant after initialization.
    Fixed,
    /// May change between steps (parameters only, through the host).
    Tunable,
    /// Changes continuously in time (inputs and outputs).
    Continuous,
}

/// One real scalar variable of the model (the layer supports fmi2Real variables only).
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// Structured name, e.g. `tip.position.x` or `beam.diameter`.
    pub name: String,
    /// Value reference: stable across versions for the same resource.
    pub vr: u32,
    /// Causality.
    pub causality: Causality,
    /// Variability.
    pub variability: Variability,
    /// Start value (parameters and inputs; `None` for calculated outputs).
    pub start: Option<f64>,
    /// SI unit symbol as used in UnitDefinitions (`m`, `N`, `N.m`, `J`, `m/s`, `m/s2`, `rad`,
    /// `s`, `Pa`, `kg/m3`, `1`, ...), `None` for dimensionless.
    pub unit: Option<&'static str>,
    /// One-line description.
    pub description: String,
    /// Outputs only: value references of the inputs this output depends on directly (at the
    /// same instant, not only through the state): ModelStructure `dependencies`, and the
    /// knowns for which fmi2GetDirectionalDerivative gives a non-zero partial derivative.
    /// Empty: no direct feedthrough.
    pub depends_on: Vec<u32>,
}

/// One String parameter of the model (fmi2String; the layer's String variables are parameters,
/// `causality="parameter"`, fixed or tunable, `initial="exact"`). Its value reference must not
/// be used by a [`Variable`] either (stricter than FMI 2.0, which numbers each type on its own:
/// a Real reference given to fmi2SetString is then named as such).
#[derive(Debug, Clone, PartialEq)]
pub struct StringVariable {
    /// Structured name, e.g. `visualization.directory`.
    pub name: String,
    /// Value reference.
    pub vr: u32,
    /// [`Variability::Fixed`] (settable before fmi2ExitInitializationMode only) or
    /// [`Variability::Tunable`] (any time).
    pub variability: Variability,
    /// Start value (the empty string is a valid start).
    pub start: String,
    /// One-line description.
    pub description: String,
}

/// Optional co-simulation capabilities (the CoSimulation flags of modelDescription.xml and
/// the calls they enable). The default offers none of them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Capabilities {
    /// Highest input derivative order used by [`CoSimModel::set_input_derivative`]: 0 = none
    /// (`canInterpolateInputs="false"`), 1 or 2 (`"true"`).
    pub input_derivative_order: u32,
    /// `maxOutputDerivativeOrder`: orders 1..=this of [`CoSimModel::get_output_derivative`].
    pub output_derivative_order: u32,
    /// `providesDirectionalDerivative`: [`CoSimModel::partial_derivative`] is implemented.
    pub directional_derivative: bool,
}

/// Identity and default experiment of a model.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelInfo {
    /// modelName attribute.
    pub model_name: String,
    /// description attribute.
    pub description: String,
    /// DefaultExperiment startTime [s].
    pub start_time: f64,
    /// DefaultExperiment stopTime [s].
    pub stop_time: f64,
    /// DefaultExperiment stepSize [s] (a preferred communication step).
    pub step_size: f64,
    /// Optional capabilities.
    pub capabilities: Capabilities,
}

/// Why a communication step did not complete. Either way the model is still in its state at
/// the start of the step (its last good state), and fmi2DoStep returns fmi2Discard with
/// fmi2LastSuccessfulTime = the start of the step.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum StepError {
    /// Recoverable (no convergence, a refusal, too much work for one call): the model can go on
    /// from its last good state with a smaller step or other inputs after fmi2SetFMUstate.
    /// fmi2Terminated stays false.
    Discard(String),
    /// The model cannot continue from its last good state at all (whatever the step or inputs):
    /// fmi2Terminated = true.
    Terminate(String),
}

impl StepError {
    /// The message.
    pub fn message(&self) -> &str {
        match self {
            StepError::Discard(m) | StepError::Terminate(m) => m,
        }
    }
}

/// A model error message is a recoverable [`StepError::Discard`].
impl From<String> for StepError {
    fn from(message: String) -> Self {
        StepError::Discard(message)
    }
}

/// What the FMI layer needs from a model.
///
/// Invariants the FMI layer relies on:
/// - `variables()` is fixed for the life of the instance and its value references are unique.
/// - `do_step` either advances the model to `t + h` and returns `Ok`, or returns `Err` and leaves
///   the model exactly in its state before the call (last good state).
/// - `save_state` bytes restored with `load_state` into a fresh instance built from the same
///   resource continue bit for bit as the original would have.
pub trait CoSimModel: Sized + Send + 'static {
    /// The file in the FMU's `resources/` folder the model is built from, e.g. `scene.toml`.
    const RESOURCE: &'static str;
    /// Name of the model family's GUID namespace (itself `UUIDv5(NAMESPACE_OID, name)`).
    const GUID_NAMESPACE: &'static str;
    /// Build identity hashed into every GUID together with the resource bytes, e.g.
    /// `model/1.2.0`: the same resource packaged by another build gets another GUID.
    const BUILD_ID: &'static str;
    /// The `generationTool` attribute of modelDescription.xml.
    const GENERATION_TOOL: &'static str;
    /// The first 8 bytes of a serialized FMU state of this model.
    const STATE_MAGIC: [u8; 8];

    /// Builds the model from the text of `resources/` [`Self::RESOURCE`]. The error names the
    /// field, the value and what is allowed.
    fn from_resource(text: &str) -> Result<Self, String>;
    /// Model name, description and default experiment.
    fn model_info(&self) -> ModelInfo;
    /// The capabilities of [`CoSimModel::model_info`], which the layer checks in the calls of
    /// every step: override it to answer without building the strings of `model_info` (no
    /// allocation in a step).
    fn capabilities(&self) -> crate::Capabilities {
        self.model_info().capabilities
    }
    /// The variable table (single source for the XML and the runtime).
    fn variables(&self) -> &[Variable];
    /// Called once at the start of every fmi2GetReal, before the values are read: a model may
    /// bring a quantity it computes only on demand up to date here. Default: nothing.
    fn before_get_real(&mut self) {}
    /// Value of the variable `variables()[index]` (the layer resolved its value reference and
    /// checked `index`). Outputs are those of the current state.
    fn get_real(&self, index: usize) -> Result<f64, String>;
    /// Sets the parameter or input `variables()[index]` (the layer resolved its value reference,
    /// checked `index` and that the variable may be set now). Refuses non-finite or
    /// out-of-range values with a message; the model is unchanged on error.
    fn set_real(&mut self, index: usize, value: f64) -> Result<(), String>;
    /// Called at fmi2ExitInitializationMode: builds the model from the current parameters and
    /// computes the initial state at `start_time`.
    fn initialize(&mut self, start_time: f64) -> Result<(), String>;
    /// Advances from `t` to `t + h` (internal substeps). On error the state is unchanged, and
    /// the error says whether the model can continue ([`StepError`]).
    fn do_step(&mut self, t: f64, h: f64) -> Result<(), StepError>;
    /// Back to the state after `from_resource` (fmi2Reset).
    fn reset(&mut self) -> Result<(), String>;
    /// Self-contained bytes: format version, resource identity, parameters, inputs, coordinates,
    /// velocities, accelerations, integrator memory.
    fn save_state(&self) -> Vec<u8>;
    /// Restores bytes from `save_state`; refuses bytes of another resource or format version.
    fn load_state(&mut self, bytes: &[u8]) -> Result<(), String>;

    /// The String parameters (none by default); value references distinct from those of
    /// [`CoSimModel::variables`]. Fixed for the life of the instance.
    fn string_variables(&self) -> &[StringVariable] {
        &[]
    }

    /// Value of the String parameter `string_variables()[index]` (the layer resolved its value
    /// reference).
    fn get_string(&self, index: usize) -> Result<&str, String> {
        let _ = index;
        Err("this model has no String variables".into())
    }

    /// Sets the String parameter `string_variables()[index]` to a copy of `value` (the layer
    /// checked that it may be set now). Also called by fmi2SetFMUstate with the state's value,
    /// after `load_state`. The model is unchanged on error.
    fn set_string(&mut self, index: usize, value: &str) -> Result<(), String> {
        let _ = (index, value);
        Err("this model has no String variables".into())
    }

    /// The instance name given at fmi2Instantiate (called once, before any other call; kept
    /// by the model across `reset`). A model may use it to name its files.
    fn set_instance_name(&mut self, name: &str) {
        let _ = name;
    }

    /// Called at fmi2Terminate (after the last step): the model may flush what it writes.
    fn terminate(&mut self) {}

    /// A warning the model has to report, taken (and cleared) by the layer after every
    /// successful fmi2ExitInitializationMode, fmi2DoStep, fmi2Terminate, fmi2Reset and
    /// fmi2SetFMUstate: the call then returns fmi2Warning and logs the message (category
    /// `logStatusWarning`). For side work that failed without harming the results (e.g. a file
    /// the model writes). `None` by default.
    fn take_warning(&mut self) -> Option<String> {
        None
    }

    /// fmi2SetRealInputDerivatives for the continuous input `variables()[index]`: its
    /// `order`-th time derivative (1 ≤ order ≤ [`Capabilities::input_derivative_order`], value
    /// finite: the layer checked both) at the current time, used over the next communication
    /// step only (the input follows u + u′τ + ½u″τ² inside it); the model forgets the
    /// derivatives of an input when that step completes or when the input is set again.
    fn set_input_derivative(&mut self, index: usize, order: u32, value: f64) -> Result<(), String> {
        let _ = (index, order, value);
        Err("input derivatives are not supported by this model".into())
    }

    /// fmi2GetRealOutputDerivatives: the `order`-th time derivative of the output
    /// `variables()[index]` at the current time (1 ≤ order ≤
    /// [`Capabilities::output_derivative_order`]).
    fn get_output_derivative(&self, index: usize, order: u32) -> Result<f64, String> {
        let _ = (index, order);
        Err("output derivatives are not supported by this model".into())
    }

    /// fmi2GetDirectionalDerivative: the partial derivative of the output `variables()[output]`
    /// with respect to the input `variables()[input]` at the current state (the input is one
    /// the output lists in [`Variable::depends_on`]; others are zero and not asked). Mutable:
    /// a model may compute and cache the partials on demand; it must not change its state.
    fn partial_derivative(&mut self, output: usize, input: usize) -> Result<f64, String> {
        let _ = (output, input);
        Err("directional derivatives are not provided by this model".into())
    }
}
