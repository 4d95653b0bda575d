//! One zstd decompression context per thread, reused: a home's prepared scene and each of its
//! face textures unpack without making and freeing a context each time (short-lived blocks
//! between long-lived ones are where glibc's heap fragments).

use std::cell::RefCell;
use zstd::bulk::Decompressor;

thread_local! {
    static CONTEXT: RefCell<Option<Decompressor<'static>>> = const { RefCell::new(None) };
}

/// Run `f` with this thread's decompressor; None when zstd cannot make one.
pub(super) fn with_decompressor<R>(f: impl FnOnce(&mut Decompressor<'static>) -> R) -> Option<R> {
    CONTEXT.with(|cell| {
        let mut cell = cell.borrow_mut();
        if cell.is_none() {
            *cell = Some(Decompressor::new().ok()?);
        }
        cell.as_mut().map(f)
    })
}

/// `data` unpacked, at most `capacity` bytes (as `zstd::bulk::decompress`).
pub(super) fn decompress(data: &[u8], capacity: usize) -> std::io::Result<Vec<u8>> {
    with_decompressor(|z| z.decompress(data, capacity))
        .unwrap_or_else(|| zstd::bulk::decompress(data, capacity))
}
