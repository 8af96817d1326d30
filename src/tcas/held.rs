//! A value that is not set yet, kept as a flag beside a placeholder, so
//! that "not set" is all-zero bytes when the placeholder is: a `static`
//! holding it goes to `.bss` (docs/firmware-and-boards.md), where `Option`
//! would put its "none" in a niche byte and the whole static in `.data`.

/// A value that may not be set yet (see the module docs).
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Held<T> {
    set: bool,
    value: T,
}

impl<T: Copy> Held<T> {
    /// Not set; `placeholder` is never read (make it all-zero bytes).
    pub(crate) const fn unset(placeholder: T) -> Self {
        Held {
            set: false,
            value: placeholder,
        }
    }

    /// The value, if set.
    pub(crate) fn get(&self) -> Option<T> {
        self.set.then_some(self.value)
    }

    /// Sets the value.
    pub(crate) fn put(&mut self, value: T) {
        self.set = true;
        self.value = value;
    }

    /// The value, if set, leaving it not set.
    pub(crate) fn take(&mut self) -> Option<T> {
        let value = self.get();
        self.set = false;
        value
    }
}

/// Equal when both are not set or both hold equal values (the placeholder
/// left behind by [`Held::take`] is not compared).
impl<T: PartialEq> PartialEq for Held<T> {
    fn eq(&self, other: &Self) -> bool {
        self.set == other.set && (!self.set || self.value == other.value)
    }
}

impl<T: Eq> Eq for Held<T> {}
