// fmt's compiled part, built once into the library. Debian ships libfmt only as a shared
// library, which would bring a dynamic libstdc++ into every process start (0.8 -> 2.5 ms for
// `imunoise --version`), and fmt's header-only mode compiles this same implementation again in
// every translation unit that formats (+3.6 s of -O3 each, a seventh of the first build). So
// every file uses fmt's ordinary headers and this one provides what they declare but do not
// define: the non-template functions (format-inl.h) and the templates format.h declares
// `extern` or leaves undefined, instantiated for the character types the headers name.
#include <fmt/format-inl.h>

FMT_BEGIN_NAMESPACE
namespace detail {

template auto dragonbox::to_decimal(float x) noexcept -> dragonbox::decimal_fp<float>;
template auto dragonbox::to_decimal(double x) noexcept -> dragonbox::decimal_fp<double>;
template locale_ref::locale_ref(const std::locale& loc);
template auto locale_ref::get<std::locale>() const -> std::locale;
template auto thousands_sep_impl<char>(locale_ref) -> thousands_sep_result<char>;
template auto thousands_sep_impl<wchar_t>(locale_ref) -> thousands_sep_result<wchar_t>;
template auto decimal_point_impl(locale_ref) -> char;
template auto decimal_point_impl(locale_ref) -> wchar_t;
template void vformat_to(buffer<char>&, string_view, basic_format_args<FMT_BUFFER_CONTEXT(char)>,
                         locale_ref);

}  // namespace detail
FMT_END_NAMESPACE
