//! The names people type for an enum's variants: one list per enum, read both ways.
//!
//! Many of iridis's options are an enum picked by name, on the command line and in Python (`--aperture periodic`,
//! `--observer 1964`). [`names!`](crate::names!) writes, from one list of a canonical name and its aliases per
//! variant, the two directions:
//!
//! * `name(self) -> &'static str`: the canonical name, as printed (in `--json`, reports, `Display`);
//! * `from_name(&str) -> Option<Self>`: the variant whose canonical name or alias equals the text, with white
//!   space around it trimmed and ASCII case ignored.
//!
//! Each crate's `FromStr` stays its own, so that an unknown name gets that crate's error and message:
//! `Self::from_name(s).ok_or_else(|| …)`.

/// Generates `name` and `from_name` for a `Copy` enum (named where it is in scope) from its variants'
/// canonical names and aliases.
///
/// Each line is `Variant => "canonical" | "alias" | …`; a variant that carries a value names it in
/// parentheses, in a form that is both a pattern and an expression (`StamPeriodic(Bump::Triangular) => "…"`).
/// The canonical name is returned as written (its case kept: `"A1"`, `"D65"`); matching ignores ASCII case
/// and trims white space, so the aliases need be written once, in any case. Earlier lines win when a name
/// would match twice. `name` is an exhaustive `match`: a variant left out of the list does not compile.
///
/// ```
/// #[derive(Debug, Clone, Copy, PartialEq, Eq)]
/// pub enum Aperture {
///     Finite,
///     Periodic,
/// }
///
/// iridis_color::names! {
///     Aperture {
///         Finite => "finite" | "patch",
///         Periodic => "periodic" | "periodic-extension",
///     }
/// }
///
/// assert_eq!(Aperture::Periodic.name(), "periodic");
/// assert_eq!(Aperture::from_name(" Patch "), Some(Aperture::Finite));
/// assert_eq!(Aperture::from_name("infinite"), None);
/// ```
#[macro_export]
macro_rules! names {
    (
        $enum:ident {
            $( $variant:ident $( ( $($value:tt)* ) )? => $canonical:literal $( | $alias:literal )* ),+ $(,)?
        }
    ) => {
        impl $enum {
            /// The canonical name of this value, as printed.
            pub const fn name(self) -> &'static str {
                match self {
                    $( $enum::$variant $( ( $($value)* ) )? => $canonical, )+
                }
            }

            /// The value whose canonical name or alias is `name` (white space around it trimmed, ASCII case
            /// ignored); `None` for any other text.
            pub fn from_name(name: &str) -> ::core::option::Option<Self> {
                let name = name.trim();
                $(
                    if name.eq_ignore_ascii_case($canonical) $( || name.eq_ignore_ascii_case($alias) )* {
                        return ::core::option::Option::Some($enum::$variant $( ( $($value)* ) )?);
                    }
                )+
                ::core::option::Option::None
            }
        }
    };
}
