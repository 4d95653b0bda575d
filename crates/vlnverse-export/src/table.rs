//! A small column-oriented Parquet table writer on the `parquet` crate's low-level API (no
//! Arrow): the column shapes a LeRobot dataset needs, laid out as pyarrow writes them
//! (every field optional; lists in the standard three-level `LIST` form; images as the
//! Hugging Face `{bytes, path}` struct), so pyarrow, `datasets` and LeRobot read the files
//! as their own.

use std::fs::File;
use std::path::Path;
use std::sync::Arc;

use parquet::basic::{Compression, ConvertedType, Encoding, LogicalType, Repetition, ZstdLevel};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, FloatType, Int64Type};
use parquet::file::metadata::KeyValue;
use parquet::file::properties::{EnabledStatistics, WriterProperties, WriterVersion};
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::{ColumnPath, Type, TypePtr};

use crate::error::{ExportError, Result};

/// Values of one leaf column with their definition and repetition levels.
enum Values {
    I64(Vec<i64>),
    F32(Vec<f32>),
    F64(Vec<f64>),
    Bytes(Vec<ByteArray>),
}

struct Leaf {
    values: Values,
    def: Vec<i16>,
    rep: Option<Vec<i16>>,
    /// Path of the leaf, for per-column encodings.
    path: Vec<String>,
    byte_stream_split: bool,
}

/// Rows of a table, built one column at a time (every column must have the same row count).
pub struct Table {
    rows: usize,
    fields: Vec<TypePtr>,
    leaves: Vec<Leaf>,
    metadata: Vec<KeyValue>,
}

fn primitive(
    name: &str,
    physical: parquet::basic::Type,
) -> parquet::schema::types::PrimitiveTypeBuilder<'_> {
    Type::primitive_type_builder(name, physical).with_repetition(Repetition::OPTIONAL)
}

fn build(t: parquet::errors::Result<Type>) -> TypePtr {
    // The builders only fail on inconsistent annotations, which this module never makes.
    Arc::new(t.expect("static Parquet schema"))
}

/// `optional group <name> (LIST) { repeated group list { <element> } }`
fn list_of(name: &str, element: TypePtr) -> TypePtr {
    let list = build(
        Type::group_type_builder("list")
            .with_repetition(Repetition::REPEATED)
            .with_fields(vec![element])
            .build(),
    );
    build(
        Type::group_type_builder(name)
            .with_repetition(Repetition::OPTIONAL)
            .with_converted_type(ConvertedType::LIST)
            .with_logical_type(Some(LogicalType::List))
            .with_fields(vec![list])
            .build(),
    )
}

fn physical_of(v: &Values) -> parquet::basic::Type {
    match v {
        Values::I64(_) => parquet::basic::Type::INT64,
        Values::F32(_) => parquet::basic::Type::FLOAT,
        Values::F64(_) => parquet::basic::Type::DOUBLE,
        Values::Bytes(_) => parquet::basic::Type::BYTE_ARRAY,
    }
}

/// A value column's element type, with the string annotation for text.
fn element(name: &str, v: &Values, text: bool) -> TypePtr {
    let b = primitive(name, physical_of(v));
    let b = if text {
        b.with_converted_type(ConvertedType::UTF8)
            .with_logical_type(Some(LogicalType::String))
    } else {
        b
    };
    build(b.build())
}

impl Table {
    /// An empty table of `rows` rows.
    pub fn new(rows: usize) -> Self {
        Table {
            rows,
            fields: Vec::new(),
            leaves: Vec::new(),
            metadata: Vec::new(),
        }
    }

    fn check(&self, name: &str, n: usize) {
        debug_assert_eq!(
            n, self.rows,
            "column {name}: {n} rows, table has {}",
            self.rows
        );
    }

    fn scalar(&mut self, name: &str, values: Values, text: bool) {
        let n = match &values {
            Values::I64(v) => v.len(),
            Values::F32(v) => v.len(),
            Values::F64(v) => v.len(),
            Values::Bytes(v) => v.len(),
        };
        self.check(name, n);
        self.fields.push(element(name, &values, text));
        self.leaves.push(Leaf {
            values,
            def: vec![1; n],
            rep: None,
            path: vec![name.to_string()],
            byte_stream_split: false,
        });
    }

    /// An `int64` column.
    pub fn i64(&mut self, name: &str, v: Vec<i64>) {
        self.scalar(name, Values::I64(v), false);
    }

    /// A `float` column.
    pub fn f32(&mut self, name: &str, v: Vec<f32>) {
        self.scalar(name, Values::F32(v), false);
    }

    /// A `double` column.
    pub fn f64(&mut self, name: &str, v: Vec<f64>) {
        self.scalar(name, Values::F64(v), false);
    }

    /// A `string` column.
    pub fn string(&mut self, name: &str, v: &[String]) {
        let v = v.iter().map(|s| ByteArray::from(s.as_str())).collect();
        self.scalar(name, Values::Bytes(v), true);
    }

    /// A list column from flat values and per-row lengths (`list<element: T>`).
    fn list(&mut self, name: &str, values: Values, lens: &[usize], text: bool) {
        self.check(name, lens.len());
        self.fields
            .push(list_of(name, element("element", &values, text)));
        let total: usize = lens.iter().sum();
        let mut def = Vec::with_capacity(total);
        let mut rep = Vec::with_capacity(total);
        for &n in lens {
            if n == 0 {
                def.push(1);
                rep.push(0);
            }
            for k in 0..n {
                def.push(3);
                rep.push(if k == 0 { 0 } else { 1 });
            }
        }
        self.leaves.push(Leaf {
            values,
            def,
            rep: Some(rep),
            path: vec![name.into(), "list".into(), "element".into()],
            byte_stream_split: false,
        });
    }

    /// A `list<float>` column, one list per row.
    pub fn list_f32(&mut self, name: &str, rows: &[Vec<f32>]) {
        let lens: Vec<usize> = rows.iter().map(Vec::len).collect();
        self.list(name, Values::F32(rows.concat()), &lens, false);
    }

    /// A `list<double>` column, one list per row.
    pub fn list_f64(&mut self, name: &str, rows: &[Vec<f64>]) {
        let lens: Vec<usize> = rows.iter().map(Vec::len).collect();
        self.list(name, Values::F64(rows.concat()), &lens, false);
    }

    /// A `list<int64>` column, one list per row.
    pub fn list_i64(&mut self, name: &str, rows: &[Vec<i64>]) {
        let lens: Vec<usize> = rows.iter().map(Vec::len).collect();
        self.list(name, Values::I64(rows.concat()), &lens, false);
    }

    /// A `list<string>` column, one list per row.
    pub fn list_string(&mut self, name: &str, rows: &[Vec<String>]) {
        let lens: Vec<usize> = rows.iter().map(Vec::len).collect();
        let v = rows
            .iter()
            .flatten()
            .map(|s| ByteArray::from(s.as_str()))
            .collect();
        self.list(name, Values::Bytes(v), &lens, true);
    }

    /// A `list<list<list<float>>>` column of `[d0, d1, d2]` arrays (row-major), as `datasets`
    /// stores an `Array3D`. Values are stored with the byte-stream-split encoding, which
    /// compresses floats far better.
    pub fn array3_f32(&mut self, name: &str, rows: &[&[f32]], dims: [usize; 3]) {
        self.check(name, rows.len());
        let per = dims[0] * dims[1] * dims[2];
        let mut values = Vec::with_capacity(per * rows.len());
        for r in rows {
            debug_assert_eq!(r.len(), per, "{name}: array of the wrong size");
            values.extend_from_slice(r);
        }
        self.nested3(name, Values::F32(values), rows.len(), dims, true);
    }

    /// A `list<list<list<double>>>` column of `[d0, d1, d2]` arrays (row-major).
    pub fn array3_f64(&mut self, name: &str, rows: &[Vec<f64>], dims: [usize; 3]) {
        self.check(name, rows.len());
        self.nested3(name, Values::F64(rows.concat()), rows.len(), dims, false);
    }

    /// Three nested lists over flat row-major `values` of `rows` arrays of shape `dims`.
    fn nested3(&mut self, name: &str, values: Values, rows: usize, dims: [usize; 3], split: bool) {
        let inner = list_of("element", element("element", &values, false));
        let middle = list_of("element", inner);
        let outer = list_of(name, middle);
        self.fields.push(outer);
        let per = dims[0] * dims[1] * dims[2];
        // Repetition level of element k of a row: where the index first changes.
        let mut levels = Vec::with_capacity(per);
        for k in 0..per {
            let c = k % dims[2];
            let w = (k / dims[2]) % dims[1];
            levels.push(if k == 0 {
                0
            } else if c > 0 {
                3
            } else if w > 0 {
                2
            } else {
                1
            });
        }
        let rep: Vec<i16> = (0..rows).flat_map(|_| levels.iter().copied()).collect();
        let def = vec![7; rep.len()];
        self.leaves.push(Leaf {
            values,
            def,
            rep: Some(rep),
            path: [
                name, "list", "element", "list", "element", "list", "element",
            ]
            .map(String::from)
            .to_vec(),
            byte_stream_split: split,
        });
    }

    /// A Hugging Face `Image` column: `struct<bytes: binary, path: string>` with the encoded
    /// image in `bytes` and a null `path`.
    pub fn image(&mut self, name: &str, encoded: Vec<Vec<u8>>) {
        self.check(name, encoded.len());
        let bytes = build(primitive("bytes", parquet::basic::Type::BYTE_ARRAY).build());
        let path = build(
            primitive("path", parquet::basic::Type::BYTE_ARRAY)
                .with_converted_type(ConvertedType::UTF8)
                .with_logical_type(Some(LogicalType::String))
                .build(),
        );
        self.fields.push(build(
            Type::group_type_builder(name)
                .with_repetition(Repetition::OPTIONAL)
                .with_fields(vec![bytes, path])
                .build(),
        ));
        let n = encoded.len();
        self.leaves.push(Leaf {
            values: Values::Bytes(encoded.into_iter().map(ByteArray::from).collect()),
            def: vec![2; n],
            rep: None,
            path: vec![name.into(), "bytes".into()],
            byte_stream_split: false,
        });
        self.leaves.push(Leaf {
            values: Values::Bytes(Vec::new()),
            def: vec![1; n],
            rep: None,
            path: vec![name.into(), "path".into()],
            byte_stream_split: false,
        });
    }

    /// A key-value entry of the file metadata (e.g. `huggingface`, `pandas`).
    pub fn metadata(&mut self, key: &str, value: String) {
        self.metadata.push(KeyValue::new(key.to_string(), value));
    }

    /// Write the table as one row group to `path` (not atomically: the caller writes to a
    /// temporary name and renames).
    pub fn write(self, path: &Path) -> Result<()> {
        let err = |e: parquet::errors::ParquetError| ExportError::Parquet {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        let schema = build(
            Type::group_type_builder("schema")
                .with_fields(self.fields)
                .build(),
        );
        let mut props = WriterProperties::builder()
            .set_writer_version(WriterVersion::PARQUET_1_0)
            .set_compression(Compression::ZSTD(ZstdLevel::try_new(3).map_err(err)?))
            .set_dictionary_enabled(false)
            .set_statistics_enabled(EnabledStatistics::Chunk)
            .set_created_by(format!("vlnverse-export {}", env!("CARGO_PKG_VERSION")));
        for leaf in &self.leaves {
            if leaf.byte_stream_split {
                props = props.set_column_encoding(
                    ColumnPath::new(leaf.path.clone()),
                    Encoding::BYTE_STREAM_SPLIT,
                );
            }
        }
        let file = File::create(path).map_err(|e| ExportError::io(path, e))?;
        let mut w =
            SerializedFileWriter::new(file, schema, Arc::new(props.build())).map_err(err)?;
        for kv in self.metadata {
            w.append_key_value_metadata(kv);
        }
        let mut rg = w.next_row_group().map_err(err)?;
        for leaf in &self.leaves {
            let Some(mut col) = rg.next_column().map_err(err)? else {
                return Err(ExportError::Parquet {
                    path: path.to_path_buf(),
                    message: "schema has fewer columns than the table".into(),
                });
            };
            let (def, rep) = (Some(leaf.def.as_slice()), leaf.rep.as_deref());
            match &leaf.values {
                Values::I64(v) => col.typed::<Int64Type>().write_batch(v, def, rep),
                Values::F32(v) => col.typed::<FloatType>().write_batch(v, def, rep),
                Values::F64(v) => col.typed::<DoubleType>().write_batch(v, def, rep),
                Values::Bytes(v) => col.typed::<ByteArrayType>().write_batch(v, def, rep),
            }
            .map_err(err)?;
            col.close().map_err(err)?;
        }
        rg.close().map_err(err)?;
        let file = w.into_inner().map_err(err)?;
        file.sync_all().map_err(|e| ExportError::io(path, e))?;
        Ok(())
    }
}
