//! A small writer of Python pickles (protocol 3): the original agent server reads every step's
//! observations with `pickle.loads`, so they must arrive as pickled dicts of numpy arrays.
//!
//! Only what observations need is written: dicts with string keys, lists, strings, numbers,
//! booleans, `None` and numpy arrays. Arrays are built by calling the public
//! `numpy.ndarray(shape, dtype, buffer)` constructor on a `bytearray` (a writable, owned
//! array on every numpy version), never through numpy's private reconstruct helpers, whose
//! module moved between numpy 1 and 2. No memo is used: nothing is shared between values.

/// Element types of the arrays sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DType {
    /// `uint8`.
    U8,
    /// `uint16`, little-endian.
    U16,
    /// `uint32`, little-endian.
    U32,
    /// `float32`, little-endian.
    F32,
    /// `int64`, little-endian.
    I64,
}

impl DType {
    /// The numpy type string (explicit byte order, so the array reads the same anywhere).
    pub fn descr(self) -> &'static str {
        match self {
            DType::U8 => "|u1",
            DType::U16 => "<u2",
            DType::U32 => "<u4",
            DType::F32 => "<f4",
            DType::I64 => "<i8",
        }
    }
    /// Bytes per element.
    pub fn size(self) -> usize {
        match self {
            DType::U8 => 1,
            DType::U16 => 2,
            DType::U32 | DType::F32 => 4,
            DType::I64 => 8,
        }
    }
}

/// A value to pickle.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// `None`.
    None,
    /// `True` / `False`.
    Bool(bool),
    /// `int`.
    Int(i64),
    /// `float`.
    Float(f64),
    /// `str`.
    Str(String),
    /// `list`.
    List(Vec<Value>),
    /// `dict` with string keys, in this order.
    Dict(Vec<(String, Value)>),
    /// A numpy array: little-endian element bytes, row-major.
    Array {
        /// Element type.
        dtype: DType,
        /// Shape.
        shape: Vec<usize>,
        /// `shape.product() * dtype.size()` bytes.
        data: Vec<u8>,
    },
}

impl Value {
    /// A `float32` array from values.
    pub fn f32_array(shape: Vec<usize>, values: &[f32]) -> Value {
        let mut data = Vec::with_capacity(values.len() * 4);
        for v in values {
            data.extend_from_slice(&v.to_le_bytes());
        }
        Value::Array {
            dtype: DType::F32,
            shape,
            data,
        }
    }
}

/// `value` as a protocol-3 pickle (readable by any Python 3).
///
/// # Panics
/// Never for well-formed arrays; an array whose byte length does not match its shape is a
/// programming error and is caught by a debug assertion.
pub fn dumps(value: &Value) -> Vec<u8> {
    let mut out = Vec::with_capacity(estimate(value) + 16);
    out.extend_from_slice(&[0x80, 3]);
    write(&mut out, value);
    out.push(b'.');
    out
}

fn estimate(v: &Value) -> usize {
    match v {
        Value::Array { data, .. } => data.len() + 96,
        Value::Str(s) => s.len() + 5,
        Value::List(l) => l.iter().map(estimate).sum::<usize>() + 2,
        Value::Dict(d) => {
            d.iter()
                .map(|(k, v)| k.len() + 5 + estimate(v))
                .sum::<usize>()
                + 2
        }
        _ => 9,
    }
}

fn write(out: &mut Vec<u8>, v: &Value) {
    match v {
        Value::None => out.push(b'N'),
        Value::Bool(true) => out.push(0x88),
        Value::Bool(false) => out.push(0x89),
        Value::Int(i) => int(out, *i),
        Value::Float(f) => {
            out.push(b'G');
            out.extend_from_slice(&f.to_be_bytes());
        }
        Value::Str(s) => string(out, s),
        Value::List(items) => {
            out.push(b']');
            if !items.is_empty() {
                out.push(b'(');
                items.iter().for_each(|i| write(out, i));
                out.push(b'e');
            }
        }
        Value::Dict(items) => {
            out.push(b'}');
            if !items.is_empty() {
                out.push(b'(');
                for (k, v) in items {
                    string(out, k);
                    write(out, v);
                }
                out.push(b'u');
            }
        }
        Value::Array { dtype, shape, data } => array(out, *dtype, shape, data),
    }
}

fn int(out: &mut Vec<u8>, i: i64) {
    if let Ok(small) = i32::try_from(i) {
        out.push(b'J');
        out.extend_from_slice(&small.to_le_bytes());
    } else {
        // LONG1: little-endian two's complement, 8 bytes are always enough for an i64.
        out.extend_from_slice(&[0x8a, 8]);
        out.extend_from_slice(&i.to_le_bytes());
    }
}

fn string(out: &mut Vec<u8>, s: &str) {
    out.push(b'X');
    out.extend_from_slice(&(s.len() as u32).to_le_bytes());
    out.extend_from_slice(s.as_bytes());
}

fn global(out: &mut Vec<u8>, module: &str, name: &str) {
    out.push(b'c');
    out.extend_from_slice(module.as_bytes());
    out.push(b'\n');
    out.extend_from_slice(name.as_bytes());
    out.push(b'\n');
}

/// `numpy.ndarray(shape, numpy.dtype(descr), bytearray(data))`.
fn array(out: &mut Vec<u8>, dtype: DType, shape: &[usize], data: &[u8]) {
    debug_assert_eq!(shape.iter().product::<usize>() * dtype.size(), data.len());
    global(out, "numpy", "ndarray");
    out.push(b'(');
    // shape tuple
    out.push(b'(');
    for &d in shape {
        int(out, d as i64);
    }
    out.push(b't');
    // dtype
    global(out, "numpy", "dtype");
    string(out, dtype.descr());
    out.push(0x85); // TUPLE1
    out.push(b'R');
    // buffer: bytearray(bytes)
    global(out, "builtins", "bytearray");
    if data.len() < 256 {
        out.extend_from_slice(&[b'C', data.len() as u8]);
    } else {
        out.push(b'B');
        out.extend_from_slice(&(data.len() as u32).to_le_bytes());
    }
    out.extend_from_slice(data);
    out.push(0x85);
    out.push(b'R');
    out.push(b't');
    out.push(b'R');
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scalars_and_containers_use_the_protocol_3_opcodes() {
        let v = Value::Dict(vec![
            ("a".into(), Value::Int(1)),
            (
                "b".into(),
                Value::List(vec![Value::Bool(true), Value::None]),
            ),
        ]);
        let bytes = dumps(&v);
        let want: Vec<u8> = [
            &[0x80, 3, b'}', b'('][..],
            &[b'X', 1, 0, 0, 0, b'a', b'J', 1, 0, 0, 0],
            &[b'X', 1, 0, 0, 0, b'b', b']', b'(', 0x88, b'N', b'e'],
            b"u.",
        ]
        .concat();
        assert_eq!(bytes, want);
    }

    #[test]
    fn large_ints_and_floats_keep_their_value() {
        let b = dumps(&Value::Int(-(1 << 40)));
        assert_eq!(&b[2..4], &[0x8a, 8]);
        assert_eq!(i64::from_le_bytes(b[4..12].try_into().unwrap()), -(1 << 40));
        let b = dumps(&Value::Float(0.1));
        assert_eq!(b[2], b'G');
        assert_eq!(f64::from_be_bytes(b[3..11].try_into().unwrap()), 0.1);
    }

    #[test]
    fn arrays_name_numpy_and_carry_their_bytes() {
        let v = Value::f32_array(vec![2, 1], &[1.5, -2.0]);
        let b = dumps(&v);
        let text = String::from_utf8_lossy(&b);
        assert!(
            text.contains("cnumpy\nndarray\n") && text.contains("<f4"),
            "{text}"
        );
        let raw: Vec<u8> = [1.5f32.to_le_bytes(), (-2.0f32).to_le_bytes()].concat();
        assert!(b.windows(raw.len()).any(|w| w == raw.as_slice()));
        // Big buffers switch from SHORT_BINBYTES to BINBYTES.
        let big = Value::Array {
            dtype: DType::U8,
            shape: vec![300],
            data: vec![7; 300],
        };
        let b = dumps(&big);
        let at = b.windows(5).position(|w| w == [b'B', 44, 1, 0, 0]).unwrap();
        assert_eq!(&b[at + 5..at + 305], &[7u8; 300][..]);
    }
}
