//! [`Named`]: a setting chosen from a fixed list by name, with the one
//! table of its values and names that scene files, the command line,
//! reports and error messages read.

use std::mem::discriminant;

/// A setting chosen by name from a fixed list — a solver, a scheme, a
/// minimiser — whose values and names are written once, in
/// [`Named::TABLE`]. Reading a name ([`Named::from_name`]), writing one
/// ([`Named::name`]) and listing the choices in a message
/// ([`Named::quoted_names`]) all go through that table, so a scene file, the
/// command line, a report and an error message cannot spell a value two
/// ways.
///
/// A value is matched to its table entry by its enum variant, so a variant
/// that carries parameters (a solver's tolerance, say) has one entry, with
/// the parameters [`Named::from_name`] gives it.
///
/// ```
/// use hooke_core::{CompressedSprings, Named};
/// assert_eq!(CompressedSprings::Exact.name(), "exact");
/// assert_eq!(CompressedSprings::from_name("clamped"), Some(CompressedSprings::Clamped));
/// assert_eq!(CompressedSprings::quoted_names(), "\"clamped\" or \"exact\"");
/// ```
pub trait Named: Copy + 'static {
    /// Every value with its name: one entry per variant, in the order
    /// messages and help texts list them.
    const TABLE: &'static [(Self, &'static str)];

    /// The value's name: that of its variant's entry in [`Named::TABLE`].
    #[must_use]
    fn name(self) -> &'static str {
        let variant = discriminant(&self);
        Self::TABLE
            .iter()
            .find(|(value, _)| discriminant(value) == variant)
            .map_or("", |&(_, name)| name)
    }

    /// The value called `name`, as [`Named::TABLE`] gives it; `None` for a
    /// name not in the table.
    #[must_use]
    fn from_name(name: &str) -> Option<Self> {
        Self::TABLE
            .iter()
            .find(|&&(_, entry)| entry == name)
            .map(|&(value, _)| value)
    }

    /// Every name, in the table's order.
    fn names() -> impl Iterator<Item = &'static str> {
        Self::TABLE.iter().map(|&(_, name)| name)
    }

    /// Every name quoted and listed for a message: `"a", "b" or "c"`.
    #[must_use]
    fn quoted_names() -> String {
        quoted_list(Self::names())
    }
}

/// `names` quoted and listed for a message: `"a", "b" or "c"` (one name
/// alone, quoted; none, empty).
///
/// ```
/// assert_eq!(hooke_core::quoted_list(["pcg", "amg"]), "\"pcg\" or \"amg\"");
/// ```
pub fn quoted_list<'a>(names: impl IntoIterator<Item = &'a str>) -> String {
    let quoted: Vec<String> = names.into_iter().map(|n| format!("\"{n}\"")).collect();
    match quoted.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}
