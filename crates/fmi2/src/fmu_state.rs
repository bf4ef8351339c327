//! FMU states: owned copies made by fmi2GetFMUstate, and their self-contained serialized form.
//!
//! Serialized format, version 2 (all integers and floats little-endian):
//!
//! | bytes | field |
//! |---|---|
//! | 8 | magic: the model's [`CoSimModel::STATE_MAGIC`] |
//! | 4 | format version (`1`) |
//! | 4 + n | GUID length, GUID (UTF-8): the state only loads into an FMU of the same resource and build |
//! | 4 | FMI state bits ([`ModelState::bits`]) |
//! | 8 × 3 | time, start time, last successful time |
//! | 1 + 8 | stop time defined (0/1), stop time |
//! | 1 + 8 | tolerance defined (0/1), tolerance |
//! | 1 | terminated (0/1) |
//! | 8 + 8 | model byte count m, String section byte count s |
//! | m | model bytes ([`CoSimModel::save_state`]) |
//! | s | String section: count (4), then per String parameter (model order) its length (4) and UTF-8 bytes |
//! | 8 | FNV-1a 64 checksum of everything before it ([`fnv1a64`]) |
//!
//! Version 1 (no String section, no count s) is still read: its state has no String values
//! and fmi2SetFMUstate keeps the current ones.
//!
//! The checksum detects accidents only (anyone can recompute it): the model checks its own
//! bytes when they are loaded.
//!
//! [`CoSimModel::save_state`]: super::model::CoSimModel::save_state
//! [`CoSimModel::STATE_MAGIC`]: super::model::CoSimModel::STATE_MAGIC

use super::hash::fnv1a64;
use super::state::{Function, ModelState};

const FORMAT_VERSION: u32 = 2;

/// Bytes of the FMI layer's fields between the GUID and the model byte count: state bits,
/// three times, stop time and tolerance (flag + value each), terminated.
const LAYER_LEN: usize = 4 + 24 + 9 + 9 + 1;

/// The FMI layer's part of an FMU state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerState {
    /// FMI state-machine state.
    pub state: ModelState,
    /// Current time.
    pub time: f64,
    /// Start time from fmi2SetupExperiment.
    pub start_time: f64,
    /// Stop time, if defined.
    pub stop_time: Option<f64>,
    /// Tolerance, if defined.
    pub tolerance: Option<f64>,
    /// Time reached by the last successful step.
    pub last_successful_time: f64,
    /// fmi2Terminated status.
    pub terminated: bool,
}

impl LayerState {
    /// The values right after fmi2Instantiate.
    pub fn instantiated() -> Self {
        Self {
            state: ModelState::INSTANTIATED,
            time: 0.0,
            start_time: 0.0,
            stop_time: None,
            tolerance: None,
            last_successful_time: 0.0,
            terminated: false,
        }
    }
}

/// An owned FMU state (what an `fmi2FMUstate` points to).
#[derive(Debug, Clone, PartialEq)]
pub struct FmuState {
    /// FMI layer part.
    pub layer: LayerState,
    /// Model bytes from `save_state`.
    pub model: Vec<u8>,
    /// The values of the model's String parameters (model order), empty if it has none.
    pub strings: Vec<String>,
}

impl FmuState {
    /// A state from its parts.
    pub fn new(layer: LayerState, model: Vec<u8>) -> Self {
        Self {
            layer,
            model,
            strings: Vec::new(),
        }
    }

    /// This state with the String parameters' values `strings`.
    pub fn with_strings(mut self, strings: Vec<String>) -> Self {
        self.strings = strings;
        self
    }

    /// Length of the String section.
    fn strings_len(&self) -> usize {
        4 + self.strings.iter().map(|s| 4 + s.len()).sum::<usize>()
    }

    /// Length of [`FmuState::serialize`]'s output.
    pub fn serialized_len(&self, guid: &str) -> usize {
        8 + 4 + 4 + guid.len() + LAYER_LEN + 16 + self.model.len() + self.strings_len() + 8
    }

    /// The self-contained bytes of this state for an FMU with this magic and GUID.
    pub fn serialize(&self, magic: &[u8; 8], guid: &str) -> Vec<u8> {
        let l = &self.layer;
        let mut b = Vec::with_capacity(self.serialized_len(guid));
        b.extend_from_slice(magic);
        b.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        b.extend_from_slice(&(guid.len() as u32).to_le_bytes());
        b.extend_from_slice(guid.as_bytes());
        b.extend_from_slice(&l.state.bits().to_le_bytes());
        for x in [l.time, l.start_time, l.last_successful_time] {
            b.extend_from_slice(&x.to_le_bytes());
        }
        for opt in [l.stop_time, l.tolerance] {
            b.push(opt.is_some() as u8);
            b.extend_from_slice(&opt.unwrap_or(0.0).to_le_bytes());
        }
        b.push(l.terminated as u8);
        b.extend_from_slice(&(self.model.len() as u64).to_le_bytes());
        b.extend_from_slice(&(self.strings_len() as u64).to_le_bytes());
        b.extend_from_slice(&self.model);
        b.extend_from_slice(&(self.strings.len() as u32).to_le_bytes());
        for s in &self.strings {
            b.extend_from_slice(&(s.len() as u32).to_le_bytes());
            b.extend_from_slice(s.as_bytes());
        }
        let sum = fnv1a64(&b);
        b.extend_from_slice(&sum.to_le_bytes());
        debug_assert_eq!(b.len(), self.serialized_len(guid));
        b
    }

    /// Parses and validates bytes from [`FmuState::serialize`] for an FMU with this magic and
    /// GUID. The model bytes are checked later by `load_state` (at fmi2SetFMUstate).
    ///
    /// The header is read forward and the length it declares is compared with `bytes.len()`
    /// before the checksum or the model bytes are touched: a host's wrong size is refused
    /// having read no more than a valid state of this FMU would occupy.
    pub fn deserialize(bytes: &[u8], magic: &[u8; 8], guid: &str) -> Result<Self, String> {
        if bytes.len() < 8 + 4 || &bytes[..8] != magic {
            return Err(
                "the bytes are not a serialized FMU state of this model (bad magic)".into(),
            );
        }
        let mut r = Reader { b: bytes, at: 8 };
        let version = r.u32()?;
        if version != FORMAT_VERSION && version != 1 {
            return Err(format!(
                "serialized state format version {version} is not supported (this FMU reads version {FORMAT_VERSION})"
            ));
        }
        let n = r.u32()? as usize;
        let g = r.take(n.min(guid.len()))?;
        if n != guid.len() || g != guid.as_bytes() {
            return Err(format!(
                "serialized state belongs to another FMU (GUID {}…), this FMU has GUID {guid}",
                String::from_utf8_lossy(g)
            ));
        }
        // the fixed-size layer fields, then the model byte count
        let mut h = Reader {
            b: bytes,
            at: r.at + LAYER_LEN,
        };
        let m = usize::try_from(h.u64()?).map_err(|_| "model length overflows")?;
        let s = if version == 1 {
            0
        } else {
            usize::try_from(h.u64()?).map_err(|_| "String section length overflows")?
        };
        let total =
            h.at.checked_add(m)
                .and_then(|x| x.checked_add(s))
                .and_then(|x| x.checked_add(8));
        if total != Some(bytes.len()) {
            return Err(format!(
                "serialized state is {} bytes, but its header declares {} (size does not match \
                 the state's own length: truncated, padded or a wrong size argument)",
                bytes.len(),
                total.map_or("more than fit in memory".to_owned(), |t| t.to_string())
            ));
        }
        let (body, sum) = bytes.split_at(bytes.len() - 8);
        let stored = u64::from_le_bytes(sum.try_into().map_err(|_| "truncated")?);
        if fnv1a64(body) != stored {
            return Err("serialized state is corrupted (checksum mismatch)".into());
        }
        let mut r = Reader { b: body, at: r.at };
        let bits = r.u32()?;
        let state = ModelState::from_bits(bits)
            .filter(|s| s.is_in(Function::SetFMUstate.allowed()))
            .ok_or_else(|| format!("serialized state has an invalid FMI state (bits {bits:#x})"))?;
        let time = r.f64()?;
        let start_time = r.f64()?;
        let last_successful_time = r.f64()?;
        let stop_time = r.opt_f64()?;
        let tolerance = r.opt_f64()?;
        let terminated = r.flag()?;
        let m = usize::try_from(r.u64()?).map_err(|_| "model length overflows")?;
        let s_len = if version == 1 {
            None
        } else {
            Some(usize::try_from(r.u64()?).map_err(|_| "String section length overflows")?)
        };
        let model = r.take(m)?.to_vec();
        let mut strings = Vec::new();
        // the section's length was checked against the size above
        let section_end = r.at + s_len.unwrap_or(0);
        let count = if s_len.is_some() { r.u32()? } else { 0 };
        for k in 0..count {
            let n = r.u32()? as usize;
            let text = std::str::from_utf8(r.take(n)?)
                .map_err(|_| format!("serialized state: String value {k} is not valid UTF-8"))?;
            if text.contains('\0') {
                return Err(format!(
                    "serialized state: String value {k} holds a NUL character"
                ));
            }
            strings.push(text.to_owned());
        }
        if r.at != section_end {
            return Err("serialized state: the String section does not match its length".into());
        }
        if r.at != body.len() {
            return Err(format!(
                "serialized state has {} unexpected trailing bytes",
                body.len() - r.at
            ));
        }
        let all = [time, start_time, last_successful_time];
        if all
            .iter()
            .chain(stop_time.iter())
            .chain(tolerance.iter())
            .any(|x| !x.is_finite())
        {
            return Err("serialized state holds a non-finite time".into());
        }
        Ok(Self::new(
            LayerState {
                state,
                time,
                start_time,
                stop_time,
                tolerance,
                last_successful_time,
                terminated,
            },
            model,
        )
        .with_strings(strings))
    }
}

struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.b.len());
        let end = end.ok_or_else(|| format!("serialized state truncated at byte {}", self.at))?;
        let s = &self.b[self.at..end];
        self.at = end;
        Ok(s)
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(
            self.take(4)?.try_into().unwrap_or_default(),
        ))
    }
    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().unwrap_or_default(),
        ))
    }
    fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_bits(self.u64()?))
    }
    fn flag(&mut self) -> Result<bool, String> {
        match self.take(1)?[0] {
            0 => Ok(false),
            1 => Ok(true),
            v => Err(format!(
                "serialized state has flag byte {v} at {}",
                self.at - 1
            )),
        }
    }
    fn opt_f64(&mut self) -> Result<Option<f64>, String> {
        let defined = self.flag()?;
        let x = self.f64()?;
        Ok(defined.then_some(x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const M: &[u8; 8] = b"TESTFMI2";

    fn sample() -> FmuState {
        FmuState::new(
            LayerState {
                state: ModelState::STEP_COMPLETE,
                time: 0.3,
                start_time: 0.0,
                stop_time: Some(2.0),
                tolerance: None,
                last_successful_time: 0.3,
                terminated: false,
            },
            vec![1, 2, 3, 4, 5],
        )
    }

    #[test]
    fn round_trip() {
        let s = sample();
        let b = s.serialize(M, "{g}");
        assert_eq!(b.len(), s.serialized_len("{g}"));
        let t = FmuState::deserialize(&b, M, "{g}").unwrap();
        assert_eq!(t.layer, s.layer);
        assert_eq!(t.model, s.model);
    }

    #[test]
    fn round_trip_with_strings_and_version_1() {
        let s = sample().with_strings(vec!["out/dir".into(), String::new(), "ä".into()]);
        let b = s.serialize(M, "{g}");
        assert_eq!(b.len(), s.serialized_len("{g}"));
        assert_eq!(FmuState::deserialize(&b, M, "{g}").unwrap(), s);
        // version 1: no String section (and no count of it)
        let v2 = sample().serialize(M, "{g}");
        let at = 8 + 4 + 4 + 3 + LAYER_LEN + 8;
        let mut v1 = v2[..at].to_vec();
        v1[8..12].copy_from_slice(&1u32.to_le_bytes());
        v1.extend_from_slice(&sample().model);
        let sum = fnv1a64(&v1);
        v1.extend_from_slice(&sum.to_le_bytes());
        assert_eq!(FmuState::deserialize(&v1, M, "{g}").unwrap(), sample());
        // a String section longer than its strings is refused
        let t = sample().with_strings(vec!["x".into()]);
        let mut c = t.serialize(M, "{g}");
        let last = c.len() - 9;
        c[last] = 0xff;
        assert!(FmuState::deserialize(&c, M, "{g}").is_err());
    }

    #[test]
    fn refuses_garbage_other_guid_and_corruption() {
        let b = sample().serialize(M, "{g}");
        assert!(FmuState::deserialize(&b, M, "{h}")
            .unwrap_err()
            .contains("GUID"));
        assert!(FmuState::deserialize(&b, b"OTHERMOD", "{g}")
            .unwrap_err()
            .contains("magic"));
        assert!(FmuState::deserialize(b"garbage", M, "{g}").is_err());
        assert!(FmuState::deserialize(&[], M, "{g}").is_err());
        assert!(FmuState::deserialize(&b[..b.len() - 1], M, "{g}").is_err());
        for i in 8..b.len() {
            let mut c = b.clone();
            c[i] ^= 0x40;
            assert!(FmuState::deserialize(&c, M, "{g}").is_err(), "flip at {i}");
        }
    }
}
