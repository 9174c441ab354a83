#ifndef softsand_base_tee_stream_h
#define softsand_base_tee_stream_h

#include <ostream>
#include <streambuf>

namespace softsand
{
  namespace base
  {
    /// A stream buffer that writes everything to two others: the screen and
    /// a run's log file.
    class TeeBuffer : public std::streambuf
    {
    public:
      TeeBuffer(std::streambuf *first, std::streambuf *second)
        : first(first)
        , second(second)
      {}

    protected:
      int
      overflow(int c) override
      {
        if (c == traits_type::eof())
          return traits_type::not_eof(c);
        const char ch = traits_type::to_char_type(c);
        const bool ok = first->sputc(ch) != traits_type::eof() &&
                        (second == nullptr ||
                         second->sputc(ch) != traits_type::eof());
        return ok ? c : traits_type::eof();
      }

      std::streamsize
      xsputn(const char *s, std::streamsize n) override
      {
        const std::streamsize written = first->sputn(s, n);
        if (second != nullptr)
          second->sputn(s, n);
        return written;
      }

      int
      sync() override
      {
        const int a = first->pubsync();
        const int b = second != nullptr ? second->pubsync() : 0;
        return (a == 0 && b == 0) ? 0 : -1;
      }

    private:
      std::streambuf *first;
      std::streambuf *second;
    };
  } // namespace base
} // namespace softsand

#endif
