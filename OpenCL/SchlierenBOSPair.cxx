// SPDX-License-Identifier: BSD-3-Clause
// BOS for the laboratory's software (docs/BENCH.md "BOS image pairs"): a BOS trace's recording and
// its undistorted background as an 8- or 16-bit grey image pair (PNG or TIFF) that OpenPIV and
// other cross-correlation codes read, with a JSON side file (the film's pixel size, the bench, the
// displacement's units and sign). No library beyond the C++ standard one: the PNG is written with
// stored (uncompressed) deflate blocks, the TIFF as one uncompressed strip.
#include "SchlierenSession.h"

#include "SchlierenEngineInternal.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

namespace schlieren
{

namespace
{

std::uint32_t Crc32(const unsigned char* p, std::size_t n, std::uint32_t crc = 0)
{
  static std::uint32_t table[256];
  static bool made = []
  {
    for (std::uint32_t i = 0; i < 256; ++i)
    {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k)
        c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      table[i] = c;
    }
    return true;
  }();
  (void)made;
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i)
    crc = table[(crc ^ p[i]) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

void Put32BE(std::string& out, std::uint32_t v)
{
  for (int s = 24; s >= 0; s -= 8)
    out += static_cast<char>((v >> s) & 0xFF);
}

void Put16LE(std::string& out, std::uint32_t v)
{
  out += static_cast<char>(v & 0xFF);
  out += static_cast<char>((v >> 8) & 0xFF);
}

void Put32LE(std::string& out, std::uint32_t v)
{
  for (int s = 0; s <= 24; s += 8)
    out += static_cast<char>((v >> s) & 0xFF);
}

/** The grey levels of `values` (nx*ny, film order: row 0 at the bottom), top row first, as
 * big-endian (PNG) or little-endian (TIFF) samples of `bits`; values clipped to [0, 1], NaN 0. */
std::string Samples(const std::vector<float>& values, int nx, int ny, int bits, bool bigEndian)
{
  const double full = bits == 16 ? 65535.0 : 255.0;
  std::string out;
  out.reserve(static_cast<std::size_t>(nx) * ny * (bits / 8));
  for (int j = ny - 1; j >= 0; --j)
    for (int i = 0; i < nx; ++i)
    {
      double v = values[static_cast<std::size_t>(j) * nx + i];
      v = std::isfinite(v) ? std::min(1.0, std::max(0.0, v)) : 0.0;
      const std::uint32_t q = static_cast<std::uint32_t>(std::floor(v * full + 0.5));
      if (bits == 8)
        out += static_cast<char>(q);
      else if (bigEndian)
      {
        out += static_cast<char>(q >> 8);
        out += static_cast<char>(q & 0xFF);
      }
      else
        Put16LE(out, q);
    }
  return out;
}

std::string EncodePng(const std::vector<float>& values, int nx, int ny, int bits)
{
  const std::string pixels = Samples(values, nx, ny, bits, true);
  const std::size_t row = static_cast<std::size_t>(nx) * (bits / 8);
  std::string raw;
  raw.reserve(pixels.size() + ny);
  for (int j = 0; j < ny; ++j)
  {
    raw += '\0'; // filter type None
    raw.append(pixels, j * row, row);
  }
  // zlib: header, stored deflate blocks of at most 65535 bytes, Adler-32
  std::string z = "\x78\x01";
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw)
  {
    a = (a + c) % 65521u;
    b = (b + a) % 65521u;
  }
  std::size_t at = 0;
  do
  {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    z += static_cast<char>(at + n == raw.size() ? 1 : 0);
    Put16LE(z, static_cast<std::uint32_t>(n));
    Put16LE(z, static_cast<std::uint32_t>(~n & 0xFFFF));
    z.append(raw, at, n);
    at += n;
  } while (at < raw.size());
  Put32BE(z, (b << 16) | a);
  std::string png = "\x89PNG\r\n\x1a\n";
  auto chunk = [&png](const char* kind, const std::string& data)
  {
    Put32BE(png, static_cast<std::uint32_t>(data.size()));
    const std::string body = std::string(kind, 4) + data;
    png += body;
    Put32BE(png, Crc32(reinterpret_cast<const unsigned char*>(body.data()), body.size()));
  };
  std::string ihdr;
  Put32BE(ihdr, static_cast<std::uint32_t>(nx));
  Put32BE(ihdr, static_cast<std::uint32_t>(ny));
  ihdr += static_cast<char>(bits);
  ihdr += std::string("\0\0\0\0", 4); // grey, deflate, adaptive filters, no interlace
  chunk("IHDR", ihdr);
  chunk("IDAT", z);
  chunk("IEND", std::string());
  return png;
}

std::string EncodeTiff(const std::vector<float>& values, int nx, int ny, int bits)
{
  const std::string pixels = Samples(values, nx, ny, bits, false);
  // header, the pixels (one strip), the resolution (1/1), the IFD
  std::string t = "II*";
  t += '\0';
  const std::uint32_t stripAt = 8, resAt = stripAt + static_cast<std::uint32_t>(pixels.size());
  const std::uint32_t ifdAt = resAt + 8;
  Put32LE(t, ifdAt);
  t += pixels;
  Put32LE(t, 1);
  Put32LE(t, 1);
  struct Tag
  {
    std::uint16_t Id, Type;
    std::uint32_t Value;
  };
  const Tag tags[] = { { 256, 4, static_cast<std::uint32_t>(nx) },
    { 257, 4, static_cast<std::uint32_t>(ny) },
    { 258, 3, static_cast<std::uint32_t>(bits) },
    { 259, 3, 1 },
    { 262, 3, 1 },
    { 273, 4, stripAt },
    { 274, 3, 1 }, // orientation: the first row is the top (the default, said for VTK's reader)
    { 277, 3, 1 },
    { 278, 4, static_cast<std::uint32_t>(ny) },
    { 279, 4, static_cast<std::uint32_t>(pixels.size()) },
    { 282, 5, resAt },
    { 283, 5, resAt },
    { 296, 3, 1 } };
  Put16LE(t, sizeof(tags) / sizeof(tags[0]));
  for (const Tag& g : tags)
  {
    Put16LE(t, g.Id);
    Put16LE(t, g.Type);
    Put32LE(t, 1);
    if (g.Type == 3)
    {
      Put16LE(t, g.Value);
      Put16LE(t, 0);
    }
    else
      Put32LE(t, g.Value);
  }
  Put32LE(t, 0); // no next IFD
  return t;
}

void WriteFile(const std::string& path, const std::string& bytes)
{
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (f)
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!f || !f.flush())
    throw Error("Writing the BOS pair: cannot write " + path + ": " + std::strerror(errno) + ".");
}

std::string Vector3(const double v[3])
{
  // + 0.0: a -0 component (of a cross product) is written as 0
  return "[" + JsonNumber(v[0] + 0.0) + ", " + JsonNumber(v[1] + 0.0) + ", " +
    JsonNumber(v[2] + 0.0) + "]";
}

} // namespace

std::vector<float> BOSBackground(const TraceSettings& traced, const FilmGeometry& film, int passes)
{
  if (passes < 1)
    throw Error("BOSBackground: the image holds no pass.");
  sch_params P;
  std::memset(&P, 0, sizeof(P));
  P.filmA0 = static_cast<float>(film.Corner[0]);
  P.filmB0 = static_cast<float>(film.Corner[1]);
  P.pixel = static_cast<float>(film.PixelSize);
  P.filmNx = film.Size[0];
  P.filmNy = film.Size[1];
  P.seed = traced.Seed;
  P.jitter = traced.Jitter ? (traced.Pattern == JitterPattern::Lattice ? 2 : 1) : 0;
  const float period = static_cast<float>(
    traced.BackgroundPeriod > 0 ? traced.BackgroundPeriod : 6.0 * film.PixelSize);
  FilmSums sums;
  sums.Resize(film.Size[0], film.Size[1]);
  sums.Passes = passes;
  const int n = film.Size[0] * film.Size[1];
  // the photons of the trace, each pass's emission point in each pixel, landing where they left
  for (int pass = 0; pass < passes; ++pass)
  {
    P.pass = pass;
    for (int pix = 0; pix < n; ++pix)
    {
      float a, b;
      sch_emit(&P, pix, &a, &b);
      sums.Weight[pix] += sch_bos_pattern(a, b, period, traced.BackgroundPattern, P.seed);
      sums.Count[pix] += 1;
    }
  }
  FilterSums(sums, traced);
  std::vector<float> out(static_cast<std::size_t>(n), 0.f);
  for (int i = 0; i < n; ++i)
    out[i] = sums.Count[i] > 0 ? static_cast<float>(sums.Weight[i] / sums.Count[i]) : 0.f;
  return out;
}

BOSPairFiles WriteBOSPair(const SessionImage& image, const BOSPairRequest& request)
{
  const char* what = "Writing the BOS pair: ";
  if (!image.HasImage)
    throw Error(std::string(what) + "there is no image: trace one first (with Cutoff BOS).");
  const TraceSettings& s = image.Traced;
  const TraceResult& r = image.Result;
  if (s.Mode != Cutoff::BOS || r.Displacement.empty())
    throw Error(std::string(what) + "the image was traced with Cutoff " + CutoffName(s.Mode) +
      ", not BOS: set Cutoff to BOS (and BackgroundDistance) and trace again.");
  if (request.Bits != 8 && request.Bits != 16)
    throw Error(std::string(what) + "a bit depth of " + std::to_string(request.Bits) +
      " is not one PIV codes read here: use 8 or 16.");
  std::string format = request.Format;
  std::transform(format.begin(),
    format.end(),
    format.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (format == "tif")
    format = "tiff";
  if (format != "png" && format != "tiff")
    throw Error(
      std::string(what) + "the format '" + request.Format + "' is not known: use png or tiff.");
  if (request.Prefix.empty() || request.Prefix.find_first_of("/\\") != std::string::npos)
    throw Error(std::string(what) + "the file name prefix '" + request.Prefix +
      "' must be a non-empty name without a folder (give the folder on its own).");
  struct stat st;
  if (request.Folder.empty() || stat(request.Folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw Error(std::string(what) + "the folder '" + request.Folder +
      "' does not exist (or is not a folder): make it first.");
  const FilmGeometry& film = r.Film;
  const int nx = film.Size[0], ny = film.Size[1];
  const int passes = image.Passes > 0 ? image.Passes : s.Passes;
  const std::vector<float> background = BOSBackground(s, film, passes);

  std::string folder = request.Folder;
  if (folder.back() != '/')
    folder += '/';
  const std::string ext = format == "png" ? ".png" : ".tif";
  BOSPairFiles files;
  files.Background = folder + request.Prefix + "_background" + ext;
  files.Recording = folder + request.Prefix + "_recording" + ext;
  files.SideFile = folder + request.Prefix + ".json";
  auto encode = [&](const std::vector<float>& v)
  {
    return format == "png" ? EncodePng(v, nx, ny, request.Bits)
                           : EncodeTiff(v, nx, ny, request.Bits);
  };

  // the displacement's range in pixels (for the side file: PIV windows must hold it)
  double maxShift = 0, meanX = 0, meanY = 0;
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double dx = r.Displacement[2 * i] / film.PixelSize,
                 dy = r.Displacement[2 * i + 1] / film.PixelSize;
    maxShift = std::max(maxShift, std::sqrt(dx * dx + dy * dy));
    meanX += dx;
    meanY += dy;
  }
  const double zd = s.BackgroundDistance - film.FrontPlane;
  double origin[2];
  film.GetImageOrigin(origin);
  const double period = s.BackgroundPeriod > 0 ? s.BackgroundPeriod : 6.0 * film.PixelSize;
  const TraceResult::CameraReadouts& cam = r.Camera;
  std::ostringstream j;
  auto base = [](const std::string& p) { return p.substr(p.find_last_of('/') + 1); };
  j << "{\n"
    << "  \"format\": \"schlieren BOS pair 1\",\n"
    << "  \"background\": " << JsonString(base(files.Background)) << ",\n"
    << "  \"recording\": " << JsonString(base(files.Recording)) << ",\n"
    << "  \"frame_a\": \"background\",\n  \"frame_b\": \"recording\",\n"
    << "  \"width\": " << nx << ",\n  \"height\": " << ny << ",\n"
    << "  \"bits\": " << request.Bits << ",\n"
    << "  \"grey_levels\": \"intensity 0..1 (the background pattern's brightness) times "
    << (request.Bits == 16 ? 65535 : 255) << ", rounded; both images on the same scale\",\n"
    << "  \"rows\": \"the first row of each file is the top of the film (film y points up, the "
       "file's rows down)\",\n"
    << "  \"pixel_size\": " << JsonNumber(film.PixelSize) << ",\n"
    << "  \"pixel_size_units\": \"world units (m) on the film plane: the plane through the "
       "volume's centre\",\n"
    << "  \"image_origin\": [" << JsonNumber(origin[0]) << ", " << JsonNumber(origin[1])
    << "],\n  \"image_origin_meaning\": \"where the centre of the bottom-left pixel (the last "
       "row's "
       "first pixel in the files) lies along film_axes x and y, world units from the world's "
       "origin: "
       "the origin of the image's vtkImageData\",\n"
    << "  \"film_axes\": {\"x\": " << Vector3(film.Right) << ", \"y\": " << Vector3(film.Up)
    << ", \"beam\": " << Vector3(film.Direction) << ", \"volume_centre\": " << Vector3(film.Center)
    << "},\n"
    << "  \"displacement\": {\n"
    << "    \"units\": \"pixels of these images (bos_displacement, in world units, is this times "
       "pixel_size)\",\n"
    << "    \"sign\": \"recording(p) = background(p - d): the dots move by +d from frame_a "
       "(background) to "
       "frame_b (recording), so PIV of (background, recording) measures +d\",\n"
    << "    \"axes\": \"d_x along the rows (film x, to the right); d_y along film y, up: in the "
       "file's "
       "row order (rows down) a PIV code reports -d_y unless it flips y itself\",\n"
    << "    \"meaning\": \"the background point the exit ray appears to come from (traced back to "
       "the "
       "background plane) minus the point it left; for a thin object at the centre plane about "
       "-Z_D "
       "times the deflection (the image's deflection array, radians)\",\n"
    << "    \"max_pixels\": " << JsonNumber(maxShift) << ",\n"
    << "    \"mean_pixels\": [" << JsonNumber(meanX / n) << ", " << JsonNumber(meanY / n) << "]\n"
    << "  },\n"
    << "  \"bench\": {\n"
    << "    \"background_distance\": " << JsonNumber(zd) << ",\n"
    << "    \"background_distance_meaning\": \"Z_D, world units from the volume's centre to the "
       "background "
       "(BackgroundDistance plus the box's front half-depth)\",\n"
    << "    \"BackgroundDistance\": " << JsonNumber(s.BackgroundDistance) << ",\n"
    << "    \"background_pattern\": " << JsonString(s.BackgroundPattern == 1 ? "Stripes" : "Dots")
    << ",\n"
    << "    \"background_period\": " << JsonNumber(period) << ",\n"
    << "    \"background_period_pixels\": " << JsonNumber(period / film.PixelSize) << ",\n"
    << "    \"seed\": " << s.Seed << ",\n"
    << "    \"wavelength_nm\": " << JsonNumber(s.Wavelength) << ",\n"
    << "    \"passes\": " << passes << ",\n"
    << "    \"camera\": "
    << JsonString(s.Camera == CameraModel::None ? "None"
           : s.Camera == CameraModel::Ideal     ? "Ideal"
                                                : "Lens");
  if (cam.Active)
  {
    j << ",\n    \"camera_focal_length\": " << JsonNumber(s.CameraFocalLength)
      << ",\n    \"f_number\": " << JsonNumber(s.FNumber)
      << ",\n    \"camera_distance\": " << JsonNumber(s.CameraDistance)
      << ",\n    \"focus_plane\": " << JsonNumber(s.FocusPlane)
      << ",\n    \"camera_magnification\": " << JsonNumber(cam.Magnification)
      << ",\n    \"sensor_pixel_size\": " << JsonNumber(cam.Magnification * film.PixelSize)
      << ",\n    \"sensor_pixel_size_meaning\": \"m on the sensor: pixel_size times "
         "camera_magnification\"";
    if (cam.BOSMagnification > 0)
      j << ",\n    \"bos_magnification\": " << JsonNumber(cam.BOSMagnification)
        << ",\n    \"bos_displacement_per_radian\": " << JsonNumber(cam.BOSDisplacementPerRadian)
        << ",\n    \"bos_pixels_per_radian\": " << JsonNumber(cam.BOSPixelsPerRadian)
        << ",\n    \"bos_blur_pixels\": " << JsonNumber(cam.BOSBlurPixels);
  }
  j << "\n  },\n"
    << "  \"background_meaning\": \"the pattern each pixel's photons left from, at the trace's own "
       "emission points and film filter, without the flow (and without a body: where a body hides "
       "the background the recording is dark)\",\n"
    << "  \"trace_report\": " << ImageReportJson(image) << "\n}\n";

  WriteFile(files.Background, encode(background));
  WriteFile(files.Recording, encode(r.Intensity));
  WriteFile(files.SideFile, j.str());
  return files;
}

} // namespace schlieren
