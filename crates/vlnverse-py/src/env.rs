//! `NativeVecEnv`: a [`RapierVecEnv`] behind Python, with batched NumPy observation buffers.

use std::path::{Path, PathBuf};
use std::sync::{Condvar, Mutex, MutexGuard};
use std::thread::{self, ThreadId};

use numpy::{
    PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyReadwriteArrayDyn, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use vlnverse_task::dataset;
use vlnverse_task::episode::{Split, Task};
use vlnverse_task::eval::{
    ActionSpace, EnvAction, EnvStep, EpisodeOrder, RapierVecEnv, RewardConfig, VecEnvConfig,
    DEFAULT_HOME_REPEAT,
};
use vlnverse_task::vocab::{Vocab, VOCAB_FILE};

use crate::actions::{discrete_count, Codec, Encoded};
use crate::layout::{self, DType, Field, Row};
use crate::{guarded, parse, py_err};

struct Inner {
    env: RapierVecEnv,
    fields: Vec<Field>,
    buffers: Vec<Py<PyAny>>,
    codec: Codec,
    vocab: Vocab,
    token_len: usize,
    vocab_source: String,
}

/// Who has the environments.
enum Slot {
    /// Free: the next call takes them.
    Ready(Box<Inner>),
    /// Taken by a call running on thread `owner`; `close` is set by a `close` that came
    /// meanwhile, and the call then drops them when it hands them back.
    Busy { owner: ThreadId, close: bool },
    /// Released by `close`.
    Closed,
}

/// A batch of VLN environments stepped natively (see the Python class `vlnverse.VectorEnv`).
///
/// One call at a time: a call takes the environments out of `slot` (leaving [`Slot::Busy`]),
/// runs with the mutex *unlocked* (releasing the GIL for the heavy work), and puts them back.
/// The mutex guards only those swaps, which never wait for the GIL, so a thread holding the
/// GIL may lock it; waiting for a running call (`close`, the read-only calls) happens on
/// `returned` with the GIL released. A `step` or `reset` that finds a call running raises
/// instead of waiting.
#[pyclass(module = "vlnverse._native")]
pub struct NativeVecEnv {
    slot: Mutex<Slot>,
    /// Signalled whenever a call hands the environments back (or drops them on `close`).
    returned: Condvar,
}

/// The environments taken out of the slot by one call; dropping it hands them back (or drops
/// them, when a `close` came meanwhile), also when the call fails or panics.
struct Lease<'a> {
    env: &'a NativeVecEnv,
    inner: Option<Box<Inner>>,
}

impl std::ops::Deref for Lease<'_> {
    type Target = Inner;
    fn deref(&self) -> &Inner {
        self.inner
            .as_deref()
            .expect("a lease holds the environments")
    }
}

impl std::ops::DerefMut for Lease<'_> {
    fn deref_mut(&mut self) -> &mut Inner {
        self.inner
            .as_deref_mut()
            .expect("a lease holds the environments")
    }
}

impl Drop for Lease<'_> {
    fn drop(&mut self) {
        let Some(inner) = self.inner.take() else {
            return;
        };
        let mut slot = self.env.lock();
        let dropped = if matches!(*slot, Slot::Busy { close: true, .. }) {
            *slot = Slot::Closed;
            Some(inner)
        } else {
            *slot = Slot::Ready(inner);
            None
        };
        drop(slot);
        self.env.returned.notify_all();
        // Dropped outside the mutex (it releases Python objects, which may run Python code).
        drop(dropped);
    }
}

/// What a call does when another call has the environments.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Busy {
    /// Raise (`step`, `reset`: the caller would be racing the running call).
    Raise,
    /// Wait for it, with the GIL released (the read-only calls).
    Wait,
}

/// The vocabulary beside the dataset, or one built from the task's training split.
fn load_vocab(dir: &Path, task: Task, split: Split) -> PyResult<(Vocab, String)> {
    let file = dir.join(VOCAB_FILE);
    if file.is_file() {
        return Ok((
            Vocab::load(&file).map_err(py_err)?,
            file.display().to_string(),
        ));
    }
    let from = if dataset::split_path(dir, task, Split::Train).is_file() {
        Split::Train
    } else {
        split
    };
    let eps = dataset::read_split(dir, task, from).map_err(py_err)?;
    Ok((
        Vocab::build(&eps),
        format!(
            "built from {}",
            dataset::split_path(dir, task, from).display()
        ),
    ))
}

/// The folder and size of a visual-reference split's images (from its first episode's).
fn reference_images(env: &RapierVecEnv) -> PyResult<Option<layout::ReferenceImages>> {
    let Some(dir) = env.settings().reference_dir.clone() else {
        return Ok(None);
    };
    let Some(first) = env
        .episodes()
        .iter()
        .find_map(|e| e.reference_image.as_ref())
    else {
        return Ok(None);
    };
    let (width, height, _) = layout::read_reference(&dir.join(first)).map_err(py_err)?;
    Ok(Some(layout::ReferenceImages { dir, width, height }))
}

fn zeros<'py>(py: Python<'py>, dtype: DType, shape: &[usize]) -> Py<PyAny> {
    match dtype {
        DType::U8 => PyArrayDyn::<u8>::zeros(py, shape, false)
            .into_any()
            .unbind(),
        DType::U16 => PyArrayDyn::<u16>::zeros(py, shape, false)
            .into_any()
            .unbind(),
        DType::U32 => PyArrayDyn::<u32>::zeros(py, shape, false)
            .into_any()
            .unbind(),
        DType::F32 => PyArrayDyn::<f32>::zeros(py, shape, false)
            .into_any()
            .unbind(),
        DType::I64 => PyArrayDyn::<i64>::zeros(py, shape, false)
            .into_any()
            .unbind(),
    }
}

/// A whole buffer, borrowed for writing.
enum Whole<'a> {
    U8(&'a mut [u8]),
    U16(&'a mut [u16]),
    U32(&'a mut [u32]),
    F32(&'a mut [f32]),
    I64(&'a mut [i64]),
}

impl<'a> Whole<'a> {
    /// The buffer cut into per-environment rows of `len` elements.
    fn rows(self, len: usize) -> Vec<Row<'a>> {
        match self {
            Whole::U8(s) => s.chunks_mut(len).map(Row::U8).collect(),
            Whole::U16(s) => s.chunks_mut(len).map(Row::U16).collect(),
            Whole::U32(s) => s.chunks_mut(len).map(Row::U32).collect(),
            Whole::F32(s) => s.chunks_mut(len).map(Row::F32).collect(),
            Whole::I64(s) => s.chunks_mut(len).map(Row::I64).collect(),
        }
    }
}

/// What one native call does to the batch.
enum Batch {
    Reset,
    Step(Vec<Option<EnvAction>>),
}

/// Write guards of the buffers, one list per element type, in field order.
#[derive(Default)]
struct Guards<'py> {
    u8: Vec<PyReadwriteArrayDyn<'py, u8>>,
    u16: Vec<PyReadwriteArrayDyn<'py, u16>>,
    u32: Vec<PyReadwriteArrayDyn<'py, u32>>,
    f32: Vec<PyReadwriteArrayDyn<'py, f32>>,
    i64: Vec<PyReadwriteArrayDyn<'py, i64>>,
}

fn guard<'py, T: numpy::Element>(
    py: Python<'py>,
    buf: &Py<PyAny>,
) -> PyResult<PyReadwriteArrayDyn<'py, T>> {
    let arr = buf
        .bind(py)
        .cast::<PyArrayDyn<T>>()
        .map_err(|e| py_err(format!("observation buffer: {e}")))?;
    arr.try_readwrite()
        .map_err(|e| py_err(format!("observation buffer is in use: {e}")))
}

fn slices<'a, T: numpy::Element>(
    g: &'a mut [PyReadwriteArrayDyn<'_, T>],
) -> PyResult<std::collections::VecDeque<&'a mut [T]>> {
    g.iter_mut()
        .map(|a| {
            a.as_slice_mut()
                .map_err(|e| py_err(format!("observation buffer: {e}")))
        })
        .collect()
}

impl Inner {
    /// Run `batch`, each environment writing its observations into its rows of the buffers
    /// on the thread that stepped it; the heavy work happens with the GIL released.
    fn run(&mut self, py: Python<'_>, batch: Batch) -> PyResult<Vec<EnvStep>> {
        let mut g = Guards::default();
        for (f, buf) in self.fields.iter().zip(&self.buffers) {
            match f.dtype {
                DType::U8 => g.u8.push(guard(py, buf)?),
                DType::U16 => g.u16.push(guard(py, buf)?),
                DType::U32 => g.u32.push(guard(py, buf)?),
                DType::F32 => g.f32.push(guard(py, buf)?),
                DType::I64 => g.i64.push(guard(py, buf)?),
            }
        }
        let (mut s8, mut s16, mut s32) =
            (slices(&mut g.u8)?, slices(&mut g.u16)?, slices(&mut g.u32)?);
        let (mut sf, mut si) = (slices(&mut g.f32)?, slices(&mut g.i64)?);
        let n = self.env.num_envs();
        // rows[i][k]: environment i's row of field k.
        let mut rows: Vec<Vec<Row<'_>>> = (0..n)
            .map(|_| Vec::with_capacity(self.fields.len()))
            .collect();
        for f in &self.fields {
            let missing = || py_err("observation buffers do not match the layout");
            let whole = match f.dtype {
                DType::U8 => Whole::U8(s8.pop_front().ok_or_else(missing)?),
                DType::U16 => Whole::U16(s16.pop_front().ok_or_else(missing)?),
                DType::U32 => Whole::U32(s32.pop_front().ok_or_else(missing)?),
                DType::F32 => Whole::F32(sf.pop_front().ok_or_else(missing)?),
                DType::I64 => Whole::I64(si.pop_front().ok_or_else(missing)?),
            };
            for (env_rows, row) in rows.iter_mut().zip(whole.rows(f.len().max(1))) {
                env_rows.push(row);
            }
        }
        let (env, fields, vocab, token_len) =
            (&mut self.env, &self.fields, &self.vocab, self.token_len);
        let sink = |s: &EnvStep, mut env_rows: Vec<Row<'_>>| {
            // The instruction changes only with the episode: encode it at the start.
            let tokens = (s.info.steps == 0)
                .then(|| vocab.encode(&s.episode.instruction.instruction_text, token_len));
            for (f, row) in fields.iter().zip(env_rows.drain(..)) {
                layout::write(f, s, tokens.as_deref(), row).map_err(|e| {
                    vlnverse_task::TaskError::invalid(
                        format!("observations.{}", f.key),
                        s.info.episode_id,
                        e,
                    )
                })?;
            }
            Ok(())
        };
        let res = py.detach(move || {
            guarded("step", || {
                match batch {
                    Batch::Reset => env.reset_all_into(rows, sink),
                    Batch::Step(actions) => env.step_into(actions, rows, sink),
                }
                .map_err(py_err)
            })
        });
        drop(g);
        res
    }

    /// The per-environment report as a dict of arrays and lists.
    fn infos<'py>(
        &self,
        py: Python<'py>,
        steps: &[EnvStep],
        reset: &[bool],
    ) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let col = |f: &dyn Fn(&EnvStep) -> f32| steps.iter().map(f).collect::<Vec<f32>>();
        let icol = |f: &dyn Fn(&EnvStep) -> i64| steps.iter().map(f).collect::<Vec<i64>>();
        let bcol = |f: &dyn Fn(&EnvStep) -> bool| steps.iter().map(f).collect::<Vec<bool>>();
        d.set_item(
            "episode_id",
            PyArray1::from_vec(py, icol(&|s| s.info.episode_id as i64)),
        )?;
        d.set_item(
            "pass",
            PyArray1::from_vec(py, icol(&|s| i64::from(s.info.pass))),
        )?;
        d.set_item(
            "steps",
            PyArray1::from_vec(py, icol(&|s| i64::from(s.info.steps))),
        )?;
        d.set_item(
            "distance_to_goal",
            PyArray1::from_vec(py, col(&|s| s.info.distance_to_goal)),
        )?;
        d.set_item(
            "collided",
            PyArray1::from_vec(py, bcol(&|s| s.info.collided)),
        )?;
        d.set_item(
            "collision",
            PyArray1::from_vec(py, bcol(&|s| s.info.noticeable)),
        )?;
        d.set_item(
            "collisions",
            PyArray1::from_vec(py, icol(&|s| i64::from(s.info.collisions))),
        )?;
        d.set_item(
            "questions_left",
            PyArray1::from_vec(py, icol(&|s| i64::from(s.info.questions_left))),
        )?;
        d.set_item("reward", PyArray1::from_vec(py, col(&|s| s.info.reward)))?;
        d.set_item(
            "terminated",
            PyArray1::from_vec(py, bcol(&|s| s.info.terminated)),
        )?;
        d.set_item(
            "truncated",
            PyArray1::from_vec(py, bcol(&|s| s.info.truncated)),
        )?;
        d.set_item("reset", PyArray1::from_vec(py, reset.to_vec()))?;
        let enc: Vec<Encoded> = steps
            .iter()
            .map(|s| self.codec.encode(&s.info.expert_action))
            .collect();
        if self.codec.space == ActionSpace::Discrete {
            let ids: Vec<i64> = enc
                .iter()
                .map(|e| if let Encoded::Id(i) = e { *i } else { 0 })
                .collect();
            d.set_item("expert_action", PyArray1::from_vec(py, ids))?;
        } else {
            let rows: Vec<Vec<f32>> = enc
                .iter()
                .map(|e| match e {
                    Encoded::Row(r) => r.to_vec(),
                    Encoded::Id(_) => vec![0.0; 3],
                })
                .collect();
            d.set_item(
                "expert_action",
                PyArray2::from_vec2(py, &rows).map_err(py_err)?,
            )?;
        }
        let strs = |f: &dyn Fn(&EnvStep) -> String| {
            PyList::new(py, steps.iter().map(f).collect::<Vec<String>>())
        };
        d.set_item("scene_id", strs(&|s| s.info.scene_id.clone())?)?;
        d.set_item(
            "instruction",
            strs(&|s| s.episode.instruction.instruction_text.clone())?,
        )?;
        d.set_item(
            "sub_instruction",
            strs(&|s| {
                let subs = &s.episode.instruction.sub_instructions;
                subs.get(s.info.sub_goal as usize)
                    .cloned()
                    .unwrap_or_default()
            })?,
        )?;
        d.set_item("oracle_answer", strs(&|s| s.info.oracle_answer.clone())?)?;
        d.set_item(
            "reference_image",
            strs(&|s| {
                s.episode
                    .reference_image
                    .as_ref()
                    .and_then(|r| {
                        self.env
                            .settings()
                            .reference_dir
                            .as_ref()
                            .map(|d| d.join(r).display().to_string())
                    })
                    .unwrap_or_default()
            })?,
        )?;
        let refused: Vec<Option<String>> = steps.iter().map(|s| s.info.refused.clone()).collect();
        d.set_item("refused", PyList::new(py, refused)?)?;
        let records: Vec<Option<String>> = steps
            .iter()
            .map(|s| {
                s.info
                    .record
                    .as_ref()
                    .map(|r| serde_json::to_string(r).unwrap_or_default())
            })
            .collect();
        d.set_item("record", PyList::new(py, records)?)?;
        Ok(d)
    }
}

#[pymethods]
impl NativeVecEnv {
    /// A batch of `num_envs` environments over `dataset/<task>/<split>`.
    #[new]
    #[pyo3(signature = (
        dataset, task, split, *, num_envs = 1, setting = "telhop", action_space = "discrete",
        profile = "vlnverse", sensors = None, mode = "eval", seed = 0, max_steps = None,
        success_distance = None, reward = "sparse", episode_ids = None, render = true,
        normalize_depth = true, instruction_length = 200, backend = None,
        home_repeat = DEFAULT_HOME_REPEAT
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        dataset: PathBuf,
        task: &str,
        split: &str,
        num_envs: usize,
        setting: &str,
        action_space: &str,
        profile: &str,
        sensors: Option<PathBuf>,
        mode: &str,
        seed: u64,
        max_steps: Option<u32>,
        success_distance: Option<f32>,
        reward: &str,
        episode_ids: Option<Vec<u64>>,
        render: bool,
        normalize_depth: bool,
        instruction_length: usize,
        backend: Option<&str>,
        home_repeat: u32,
    ) -> PyResult<Self> {
        let task: Task = parse("task", task)?;
        let split: Split = parse("split", split)?;
        let protocol = crate::protocol(
            setting,
            action_space,
            profile,
            sensors,
            seed,
            render,
            backend,
            max_steps,
            success_distance,
        )?;
        let (setting, space) = (protocol.setting, protocol.action_space);
        let order = match mode {
            "eval" => EpisodeOrder::Eval,
            "train" => EpisodeOrder::Train,
            other => {
                return Err(py_err(format!(
                    "invalid mode `{other}`: expected eval or train"
                )))
            }
        };
        let reward = match reward {
            "sparse" => RewardConfig::default(),
            "dense" => RewardConfig::dense(),
            other => {
                return Err(py_err(format!(
                    "invalid reward `{other}`: expected sparse or dense"
                )))
            }
        };
        if !dataset.is_dir() {
            return Err(py_err(format!(
                "dataset {}: no such folder (generate one with vlnverse.generate or `cargo \
                 xtask generate --preset tiny --out DIR`)",
                dataset.display()
            )));
        }
        if !(1..=4096).contains(&instruction_length) {
            return Err(py_err(format!(
                "invalid instruction_length {instruction_length}: must be in [1, 4096]"
            )));
        }
        let cfg = VecEnvConfig {
            dataset: dataset.clone(),
            task,
            split,
            protocol: protocol.clone(),
            num_envs,
            order,
            episode_ids,
            reward,
            home_repeat,
        };
        let (vocab, vocab_source) = load_vocab(&dataset, task, split)?;
        let env = py.detach(|| guarded("VecEnv", || RapierVecEnv::new(cfg).map_err(py_err)))?;
        let rig = env.rig().map(|r| r.config().clone());
        let reference = match task {
            Task::VisualReference => reference_images(&env)?,
            _ => None,
        };
        let fields = layout::fields(
            rig.as_ref(),
            normalize_depth,
            instruction_length,
            reference.as_ref(),
        );
        let buffers = fields
            .iter()
            .map(|f| {
                let mut shape = vec![num_envs];
                shape.extend(&f.shape);
                zeros(py, f.dtype, &shape)
            })
            .collect();
        let codec = Codec {
            space,
            setting,
            agent: env.settings().agent.clone(),
            ask: task == Task::Dialogue,
        };
        Ok(NativeVecEnv::new_ready(Inner {
            env,
            fields,
            buffers,
            codec,
            vocab,
            token_len: instruction_length,
            vocab_source,
        }))
    }

    /// What the batch offers: observation fields, action space, sizes.
    fn spec<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.with(py, |inner| {
            let d = PyDict::new(py);
            let fields = PyList::empty(py);
            for f in &inner.fields {
                fields.append((f.key.clone(), f.dtype.numpy(), f.shape.clone()))?;
            }
            d.set_item("fields", fields)?;
            let env = &inner.env;
            let cfg = env.config();
            d.set_item("num_envs", env.num_envs())?;
            d.set_item("task", cfg.task.name())?;
            d.set_item("split", cfg.split.name())?;
            d.set_item("setting", cfg.protocol.setting.name())?;
            d.set_item("action_space", cfg.protocol.action_space.name())?;
            d.set_item("discrete_actions", discrete_count(inner.codec.ask))?;
            d.set_item("episodes", env.episodes().len())?;
            d.set_item("max_steps", cfg.protocol.max_steps)?;
            d.set_item("success_distance", cfg.protocol.success_distance)?;
            d.set_item("vocab_size", inner.vocab.len())?;
            d.set_item("vocab_source", inner.vocab_source.clone())?;
            d.set_item("instruction_length", inner.token_len)?;
            let a = &inner.codec.agent;
            d.set_item("max_linear_speed", a.max_linear_speed)?;
            d.set_item("max_angular_speed", a.max_angular_speed_deg.to_radians())?;
            d.set_item(
                "renderer",
                env.rig()
                    .map_or_else(|| "none".to_string(), |r| r.backend_name()),
            )?;
            d.set_item(
                "episode_ids",
                env.episodes()
                    .iter()
                    .map(|e| e.episode_id)
                    .collect::<Vec<u64>>(),
            )?;
            Ok(d)
        })
    }

    /// The observation buffers (one array per key, first axis = environment). They are
    /// overwritten in place by every `reset` and `step`.
    fn buffers<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.with(py, |inner| {
            let d = PyDict::new(py);
            for (f, b) in inner.fields.iter().zip(&inner.buffers) {
                d.set_item(&f.key, b.bind(py))?;
            }
            Ok(d)
        })
    }

    /// The vocabulary's tokens (id = position).
    fn vocab(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        self.with(py, |inner| Ok(inner.vocab.tokens().to_vec()))
    }

    /// Reset every environment (with `seed`: reseed the episode draws and restart the eval
    /// order first). Returns the per-environment report.
    #[pyo3(signature = (seed = None))]
    fn reset<'py>(&self, py: Python<'py>, seed: Option<u64>) -> PyResult<Bound<'py, PyDict>> {
        self.with_mut(py, "reset", |inner| {
            if let Some(s) = seed {
                inner.env.seed(s);
            }
            let steps = inner.run(py, Batch::Reset)?;
            let n = steps.len();
            inner.infos(py, &steps, &vec![true; n])
        })
    }

    /// Step every environment. `actions`: int64 `(N,)` for the discrete space, float32
    /// `(N, 3)` for the box spaces; `reset_mask[i]` resets environment `i` instead of acting.
    fn step<'py>(
        &self,
        py: Python<'py>,
        actions: &Bound<'py, PyAny>,
        reset_mask: Vec<bool>,
    ) -> PyResult<Bound<'py, PyDict>> {
        self.with_mut(py, "step", |inner| {
            let n = inner.env.num_envs();
            if reset_mask.len() != n {
                return Err(py_err(format!(
                    "reset_mask has {} entries, expected {n}",
                    reset_mask.len()
                )));
            }
            let parsed: Vec<Result<EnvAction, String>> =
                if inner.codec.space == ActionSpace::Discrete {
                    let a = actions
                        .cast::<PyArray1<i64>>()
                        .map_err(|_| py_err("actions: expected an int64 array of shape (N,)"))?
                        .readonly();
                    let a = a.as_slice().map_err(py_err)?;
                    if a.len() != n {
                        return Err(py_err(format!(
                            "actions has {} entries, expected {n}",
                            a.len()
                        )));
                    }
                    a.iter()
                        .enumerate()
                        .map(|(i, &id)| inner.codec.discrete(i, id))
                        .collect()
                } else {
                    let a = actions
                        .cast::<PyArray2<f32>>()
                        .map_err(|_| py_err("actions: expected a float32 array of shape (N, 3)"))?
                        .readonly();
                    if a.shape() != [n, 3] {
                        return Err(py_err(format!(
                            "actions has shape {:?}, expected ({n}, 3)",
                            a.shape()
                        )));
                    }
                    let a = a.as_slice().map_err(py_err)?;
                    a.chunks(3)
                        .enumerate()
                        .map(|(i, r)| inner.codec.boxed(i, r))
                        .collect()
                };
            let mut batch = Vec::with_capacity(n);
            for (i, p) in parsed.into_iter().enumerate() {
                if reset_mask[i] {
                    batch.push(None);
                } else {
                    batch.push(Some(p.map_err(py_err)?));
                }
            }
            let steps = inner.run(py, Batch::Step(batch))?;
            inner.infos(py, &steps, &reset_mask)
        })
    }

    /// Release the environments (further calls raise). A `step` or `reset` running in another
    /// thread is waited for (with the GIL released); one running in this thread (close from a
    /// finalizer) releases them when it returns.
    fn close(&self, py: Python<'_>) {
        let me = thread::current().id();
        let mut slot = self.lock();
        let wait = match &mut *slot {
            Slot::Ready(_) => {
                let Slot::Ready(inner) = std::mem::replace(&mut *slot, Slot::Closed) else {
                    unreachable!("matched Ready")
                };
                drop(slot);
                self.returned.notify_all();
                // Dropped outside the mutex (it releases Python objects).
                drop(inner);
                return;
            }
            Slot::Busy { owner, close } => {
                *close = true;
                *owner != me
            }
            Slot::Closed => false,
        };
        drop(slot);
        if wait {
            py.detach(|| {
                let mut slot = self.lock();
                while !matches!(*slot, Slot::Closed) {
                    slot = self.returned.wait(slot).unwrap_or_else(|p| p.into_inner());
                }
            });
        }
    }

    /// Whether `close` was called (the environments may still be finishing a call then).
    #[getter]
    fn closed(&self) -> bool {
        matches!(*self.lock(), Slot::Closed | Slot::Busy { close: true, .. })
    }
}

impl NativeVecEnv {
    fn new_ready(inner: Inner) -> Self {
        NativeVecEnv {
            slot: Mutex::new(Slot::Ready(Box::new(inner))),
            returned: Condvar::new(),
        }
    }

    /// The slot (a panic while it was locked leaves a consistent slot: every swap is whole).
    fn lock(&self) -> MutexGuard<'_, Slot> {
        self.slot.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Take the environments for one call (`what` names it in the errors).
    fn lease(&self, py: Python<'_>, what: &str, busy: Busy) -> PyResult<Lease<'_>> {
        let me = thread::current().id();
        loop {
            let mut slot = self.lock();
            match &*slot {
                Slot::Ready(_) => {
                    let taken = std::mem::replace(
                        &mut *slot,
                        Slot::Busy {
                            owner: me,
                            close: false,
                        },
                    );
                    let Slot::Ready(inner) = taken else {
                        unreachable!("matched Ready")
                    };
                    return Ok(Lease {
                        env: self,
                        inner: Some(inner),
                    });
                }
                Slot::Closed | Slot::Busy { close: true, .. } => {
                    return Err(py_err("the environment is closed"));
                }
                Slot::Busy { owner, .. } if *owner == me || busy == Busy::Raise => {
                    let whose = if *owner == me {
                        "this thread"
                    } else {
                        "another thread"
                    };
                    return Err(py_err(format!(
                        "{what}: another call (a step or reset) is in progress on this \
                         environment in {whose}; a VectorEnv takes one call at a time \
                         (use one VectorEnv per thread, or a lock)"
                    )));
                }
                Slot::Busy { .. } => {
                    drop(slot);
                    // Wait for the running call with the GIL released (it may need the GIL
                    // to finish), then try again.
                    py.detach(|| {
                        let mut slot = self.lock();
                        while matches!(*slot, Slot::Busy { close: false, owner } if owner != me) {
                            slot = self.returned.wait(slot).unwrap_or_else(|p| p.into_inner());
                        }
                    });
                }
            }
        }
    }

    /// A read-only call (waits for a running `step` or `reset` in another thread).
    fn with<T>(&self, py: Python<'_>, f: impl FnOnce(&Inner) -> PyResult<T>) -> PyResult<T> {
        let lease = self.lease(py, "read", Busy::Wait)?;
        f(&lease)
    }

    /// A call that changes the environments (raises while another call runs).
    fn with_mut<T>(
        &self,
        py: Python<'_>,
        what: &str,
        f: impl FnOnce(&mut Inner) -> PyResult<T>,
    ) -> PyResult<T> {
        let mut lease = self.lease(py, what, Busy::Raise)?;
        f(&mut lease)
    }
}
