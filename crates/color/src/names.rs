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
//! An unknown name gets the error type and message of the crate that owns the enum. The optional clause
//! `else |s| -> Error { … }` after the list names that type and builds the error from the text `s` as given
//! (untrimmed); with it the macro also writes `impl FromStr`: `from_name(s)`, or else that error.

/// Generates `name` and `from_name` for a `Copy` enum (named where it is in scope) from its variants'
/// canonical names and aliases, and with an `else` clause also `impl FromStr`.
///
/// Each line is `Variant => "canonical" | "alias" | …`; a variant that carries a value names it in
/// parentheses, in a form that is both a pattern and an expression (`StamPeriodic(Bump::Triangular) => "…"`).
/// The canonical name is returned as written (its case kept: `"A1"`, `"D65"`); matching ignores ASCII case
/// and trims white space, so the aliases need be written once, in any case. Earlier lines win when a name
/// would match twice. `name` is an exhaustive `match`: a variant left out of the list does not compile.
///
/// The optional clause after the list, `else |s| -> Error { … }`, reads like a closure: `s` names the text
/// that matched no name (as given, before trimming), `Error` is `FromStr::Err`, and the block builds that
/// error. The generated `from_str(s)` is `Self::from_name(s).ok_or_else(|| { … })`.
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
///     else |s| -> String { format!("aperture '{s}': expected finite or periodic") }
/// }
///
/// assert_eq!(Aperture::Periodic.name(), "periodic");
/// assert_eq!(Aperture::from_name(" Patch "), Some(Aperture::Finite));
/// assert_eq!(Aperture::from_name("infinite"), None);
/// assert_eq!("Periodic-Extension".parse(), Ok(Aperture::Periodic));
/// assert_eq!("infinite".parse::<Aperture>(), Err("aperture 'infinite': expected finite or periodic".to_string()));
/// ```
#[macro_export]
macro_rules! names {
    (
        $enum:ident {
            $( $variant:ident $( ( $($value:tt)* ) )? => $canonical:literal $( | $alias:literal )* ),+ $(,)?
        }
        $( else | $text:ident | -> $error:ty $unknown:block )?
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

        $(
            impl ::core::str::FromStr for $enum {
                type Err = $error;

                /// The value named `from_name`; an unknown name is an error that quotes it.
                fn from_str($text: &str) -> ::core::result::Result<Self, $error> {
                    Self::from_name($text).ok_or_else(|| $unknown)
                }
            }
        )?
    };
}
