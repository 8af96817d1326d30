//! Saturating counters: the counts these helpers keep stop at their type's
//! maximum instead of wrapping; a list of counters is declared once
//! ([`counter_list!`]).

/// Adds one to `counter`, saturating.
pub(crate) fn increment(counter: &mut u32) {
    *counter = counter.saturating_add(1);
}

/// Adds one to a 16-bit `counter` (a wire frame's), saturating.
pub(crate) fn increment16(counter: &mut u16) {
    *counter = counter.saturating_add(1);
}

/// `n` as a `u32`, saturated.
pub(crate) fn sat_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// `n` as a `u16`, saturated.
pub(crate) fn sat_u16(n: u32) -> u16 {
    u16::try_from(n).unwrap_or(u16::MAX)
}

/// Declares a list of counters once: the struct, its names and labels in
/// wire order, the wire encoding ([`crate::wire::WireValue`]), the log line
/// (`defmt::Format`, non-zero counters) and the text ([`core::fmt::Display`],
/// every counter), so that none of them can drift from the others.
macro_rules! counter_list {
    (
        $(#[$meta:meta])*
        pub struct $name:ident: $int:ty {
            $( $(#[doc = $doc:literal])* $field:ident => $label:literal, )+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
        pub struct $name {
            $( $(#[doc = $doc])* pub $field: $int, )+
        }

        impl $name {
            /// Number of counters.
            pub const LEN: usize = [$(stringify!($field)),+].len();
            /// Field names in wire order (CSV column names).
            pub const NAMES: [&'static str; Self::LEN] = [$(stringify!($field)),+];
            /// What each counter counts, in wire order (log and text).
            pub const LABELS: [&'static str; Self::LEN] = [$($label),+];

            /// All zero.
            pub const fn new() -> Self {
                Self::from_values([0; Self::LEN])
            }
            /// The values in wire order.
            pub const fn values(&self) -> [$int; Self::LEN] {
                [$(self.$field),+]
            }
            /// From values in wire order.
            pub const fn from_values(values: [$int; Self::LEN]) -> Self {
                let [$($field),+] = values;
                Self { $($field),+ }
            }
            /// The counters added one by one, saturating.
            pub fn saturating_add(self, other: Self) -> Self {
                let mut sum = self.values();
                for (s, o) in sum.iter_mut().zip(other.values()) {
                    *s = s.saturating_add(o);
                }
                Self::from_values(sum)
            }
        }

        impl $crate::wire::WireValue for $name {
            const WIDTH: usize = Self::LEN.saturating_mul(<$int as $crate::wire::WireValue>::WIDTH);
            fn read(bytes: &[u8]) -> Self {
                let mut values = [0; Self::LEN];
                for (v, chunk) in values
                    .iter_mut()
                    .zip(bytes.chunks(<$int as $crate::wire::WireValue>::WIDTH))
                {
                    *v = <$int as $crate::wire::WireValue>::read(chunk);
                }
                Self::from_values(values)
            }
            fn write(self, bytes: &mut [u8]) {
                for (v, chunk) in self
                    .values()
                    .into_iter()
                    .zip(bytes.chunks_mut(<$int as $crate::wire::WireValue>::WIDTH))
                {
                    v.write(chunk);
                }
            }
        }

        impl core::fmt::Display for $name {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                for (i, (value, label)) in self.values().into_iter().zip(Self::LABELS).enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{value} {label}")?;
                }
                Ok(())
            }
        }

        #[cfg(feature = "defmt")]
        impl defmt::Format for $name {
            fn format(&self, f: defmt::Formatter) {
                let mut first = true;
                for (value, label) in self.values().into_iter().zip(Self::LABELS) {
                    if value == 0 {
                        continue;
                    }
                    if !first {
                        defmt::write!(f, ", ");
                    }
                    defmt::write!(f, "{} {=str}", value, label);
                    first = false;
                }
                if first {
                    defmt::write!(f, "all zero");
                }
            }
        }
    };
}
