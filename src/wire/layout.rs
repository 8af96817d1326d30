use super::*;

/// A value with a fixed big-endian encoding: an integer, or a list of
/// counters ([`ScanCounts`], ...).
pub trait WireValue: Copy {
    /// Bytes on the wire.
    const WIDTH: usize;
    /// Reads the value from `bytes` (exactly `WIDTH` of them; a shorter
    /// slice reads as zeros where bytes are missing). Never panics.
    fn read(bytes: &[u8]) -> Self;
    /// Writes the value into `bytes` (as many of its bytes as fit).
    fn write(self, bytes: &mut [u8]);
}

macro_rules! wire_int {
    ($($t:ty),*) => {$(
        impl WireValue for $t {
            const WIDTH: usize = core::mem::size_of::<$t>();
            fn read(bytes: &[u8]) -> Self {
                let mut be = [0u8; core::mem::size_of::<$t>()];
                // Element by element: `copy_from_slice` would keep a
                // length-check panic path.
                for (b, src) in be.iter_mut().zip(bytes) {
                    *b = *src;
                }
                <$t>::from_be_bytes(be)
            }
            fn write(self, bytes: &mut [u8]) {
                for (dst, b) in bytes.iter_mut().zip(self.to_be_bytes()) {
                    *dst = b;
                }
            }
        }
    )*};
}
wire_int!(u8, u16, i16, u32, i32);

/// A named field of a layout: its offset and, in the type, its encoding
/// (smoltcp's `mod field`, with the width checked by the type).
#[derive(Debug)]
pub struct Field<T> {
    start: usize,
    _value: PhantomData<fn() -> T>,
}

impl<T> Clone for Field<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Field<T> {}

impl<T: WireValue> Field<T> {
    /// The field at `start`.
    pub const fn at(start: usize) -> Self {
        Field {
            start,
            _value: PhantomData,
        }
    }
    /// First byte.
    pub const fn start(self) -> usize {
        self.start
    }
    /// One past the last byte: where the next field starts.
    pub const fn end(self) -> usize {
        self.start.saturating_add(T::WIDTH)
    }
    /// Reads the field of `bytes` (0 for bytes beyond the end). Never
    /// panics.
    pub fn get(self, bytes: &[u8]) -> T {
        T::read(bytes.get(self.start..).unwrap_or(&[]))
    }
    /// Writes the field into `bytes` (the part that fits). Never panics.
    pub fn set(self, bytes: &mut [u8], value: T) {
        if let Some(dst) = bytes.get_mut(self.start..) {
            value.write(dst);
        }
    }
}

/// Declares a layout: each field's offset is the end of the one before,
/// `LEN` is the end of the last, and `FIELDS` lists them (name, offset,
/// width, doc) for the documentation (`frames layout`).
macro_rules! layout {
    (
        $(#[$meta:meta])*
        pub mod $name:ident { $( $(#[doc = $doc:literal])* $field:ident: $t:ty, )* }
    ) => {
        $(#[$meta])*
        pub mod $name {
            #[allow(unused_imports)]
            use super::super::*;
            layout!(@fields 0usize; $( $(#[doc = $doc])* $field: $t, )*);
            /// Every field: name, offset, width, what it holds.
            pub const FIELDS: &[FieldRow] = &[
                $( (stringify!($field), $field.start(), <$t as WireValue>::WIDTH, concat!($($doc),*)), )*
            ];
        }
    };
    (@fields $at:expr;) => {
        /// Bytes in the layout.
        pub const LEN: usize = $at;
    };
    (@fields $at:expr; $(#[doc = $doc:literal])* $field:ident: $t:ty, $($rest:tt)*) => {
        $(#[doc = $doc])*
        pub const $field: Field<$t> = Field::at($at);
        layout!(@fields $field.end(); $($rest)*);
    };
}

/// A field of a layout, for the documentation: name, offset, width, what it
/// holds.
pub type FieldRow = (&'static str, usize, usize, &'static str);

/// Every layout: (name, type byte if a message, fields), for the
/// documentation (`frames layout`).
pub const LAYOUTS: [(&str, Option<FrameKind>, &[FieldRow]); 7] = [
    ("frame header", None, header::FIELDS),
    (
        "Cartesian measurement",
        Some(FrameKind::MeasurementCartesian),
        cartesian::FIELDS,
    ),
    (
        "polar measurement",
        Some(FrameKind::MeasurementPolar),
        polar::FIELDS,
    ),
    ("end of input", Some(FrameKind::EndOfInput), end::FIELDS),
    ("track report", Some(FrameKind::TrackReport), track::FIELDS),
    ("scan summary", Some(FrameKind::ScanSummary), scan::FIELDS),
    ("health", Some(FrameKind::Health), health::FIELDS),
];
