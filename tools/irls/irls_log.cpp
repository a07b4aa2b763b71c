// The batch estimate over a run's log (see irls_log.hpp).
#include "irls_log.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace mrqp::irls {

namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

bool startsWith(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }
bool endsWith(const std::string& s, const std::string& p) {
  return s.size() >= p.size() && s.compare(s.size() - p.size(), p.size(), p) == 0;
}

std::string number(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

struct Columns {
  std::vector<int> theta, theta_std;
  std::vector<std::vector<int>> rows;  // per row of μ: p columns then the μ column
  int accepted = -1;
};

}  // namespace

std::vector<EntityBatch> readBatches(const std::string& csv_path) {
  std::ifstream in(csv_path);
  if (!in) throw std::runtime_error(csv_path + ": cannot read");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(csv_path + ":1: empty file");
  const std::vector<std::string> header = splitCsv(line);
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < header.size(); ++i) index[header[i]] = static_cast<int>(i);
  auto col = [&](const std::string& name) {
    const auto it = index.find(name);
    return it == index.end() ? -1 : it->second;
  };

  // Entities: est_E_accepted columns; their state names from est_E_theta_std_NAME.
  std::vector<EntityBatch> out;
  std::vector<Columns> cols;
  for (const std::string& h : header) {
    if (!startsWith(h, "est_") || !endsWith(h, "_accepted")) continue;
    EntityBatch b;
    b.entity = h.substr(4, h.size() - 4 - 9);
    const std::string base = "est_" + b.entity;
    Columns c;
    c.accepted = col(h);
    for (const std::string& k : header) {
      if (startsWith(k, base + "_theta_std_")) b.names.push_back(k.substr(base.size() + 11));
    }
    if (b.names.empty()) throw std::runtime_error(csv_path + ":1: " + h + ": no est_" + b.entity + "_theta_std_* columns");
    for (const std::string& n : b.names) {
      c.theta.push_back(col(base + "_theta_" + n));
      c.theta_std.push_back(col(base + "_theta_std_" + n));
      if (c.theta.back() < 0) throw std::runtime_error(csv_path + ":1: missing column " + base + "_theta_" + n);
    }
    for (int r = 0;; ++r) {
      const std::string row = base + "_row" + std::to_string(r) + "_";
      if (col(row + "mu") < 0) break;
      std::vector<int> rc;
      for (const std::string& n : b.names) {
        rc.push_back(col(row + n));
        if (rc.back() < 0) throw std::runtime_error(csv_path + ":1: missing column " + row + n);
      }
      rc.push_back(col(row + "mu"));
      c.rows.push_back(rc);
    }
    if (c.rows.empty()) throw std::runtime_error(csv_path + ":1: no regression columns " + base + "_row0_*");
    out.push_back(b);
    cols.push_back(c);
  }
  if (out.empty())
    throw std::runtime_error(csv_path + ":1: no estimation columns (est_ENTITY_accepted): was the run made with "
                                        "an estimation section?");

  std::vector<std::vector<double>> ys(out.size()), mus(out.size());
  std::vector<std::string> first, last;
  long line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    std::vector<std::string> cells = splitCsv(line);
    if (cells.size() != header.size())
      throw std::runtime_error(csv_path + ":" + std::to_string(line_no) + ": " + std::to_string(cells.size()) +
                               " fields, the header has " + std::to_string(header.size()));
    auto value = [&](int c) {
      const std::string& s = cells[static_cast<std::size_t>(c)];
      char* end = nullptr;
      const double v = std::strtod(s.c_str(), &end);
      if (s.empty() || end == s.c_str() || *end != '\0') {
        if (s == "nan" || s == "-nan") return std::nan("");
        throw std::runtime_error(csv_path + ":" + std::to_string(line_no) + ": " + header[static_cast<std::size_t>(c)] +
                                 ": not a number: '" + s + "'");
      }
      return v;
    };
    if (first.empty()) first = cells;
    last = cells;
    for (std::size_t e = 0; e < out.size(); ++e) {
      if (value(cols[e].accepted) != 1.0) continue;
      ++out[e].updates;
      for (const std::vector<int>& rc : cols[e].rows) {
        for (std::size_t k = 0; k + 1 < rc.size(); ++k) ys[e].push_back(value(rc[k]));
        mus[e].push_back(value(rc.back()));
      }
    }
  }
  if (first.empty()) throw std::runtime_error(csv_path + ":2: no data rows");
  for (std::size_t e = 0; e < out.size(); ++e) {
    EntityBatch& b = out[e];
    const auto p = static_cast<Eigen::Index>(b.names.size());
    const auto n = static_cast<Eigen::Index>(mus[e].size());
    b.Y = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(ys[e].data(), n, p);
    b.mu = Eigen::Map<const Eigen::VectorXd>(mus[e].data(), n);
    b.prior.resize(p);
    b.prior_std.resize(p);
    b.online.resize(p);
    b.online_std.resize(p);
    for (Eigen::Index k = 0; k < p; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      b.prior(k) = std::strtod(first[static_cast<std::size_t>(cols[e].theta[kk])].c_str(), nullptr);
      b.prior_std(k) = std::strtod(first[static_cast<std::size_t>(cols[e].theta_std[kk])].c_str(), nullptr);
      b.online(k) = std::strtod(last[static_cast<std::size_t>(cols[e].theta[kk])].c_str(), nullptr);
      b.online_std(k) = std::strtod(last[static_cast<std::size_t>(cols[e].theta_std[kk])].c_str(), nullptr);
    }
  }
  return out;
}

BatchResult estimate(const EntityBatch& b, bool with_prior, const estimation::IrlsOptions& options) {
  BatchResult r;
  r.batch = b;
  const Eigen::Index p = b.Y.cols(), n = b.Y.rows();
  if (n == 0) throw std::runtime_error("entity '" + b.entity + "': no accepted update in the log");
  Eigen::MatrixXd Y = b.Y;
  Eigen::VectorXd mu = b.mu;
  if (with_prior) {
    if (!(b.prior_std.minCoeff() > 0.0) || !b.prior.allFinite())
      throw std::runtime_error("entity '" + b.entity + "': the log's first row has no valid prior");
    Y.conservativeResize(n + p, p);
    mu.conservativeResize(n + p);
    Y.bottomRows(p) = b.prior_std.cwiseInverse().asDiagonal();
    mu.tail(p) = b.prior.cwiseQuotient(b.prior_std);
  }
  r.irls = estimation::irlsEstimate(Y, mu, Eigen::VectorXd::Ones(Y.rows()), options);
  r.batch_std = r.irls.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  return r;
}

std::string toJson(const std::vector<BatchResult>& results, bool with_prior, double huber_k) {
  std::string s = "{\n";
  for (std::size_t e = 0; e < results.size(); ++e) {
    const BatchResult& r = results[e];
    const EntityBatch& b = r.batch;
    s += "  \"" + b.entity + "\": {\n";
    s += "    \"updates\": " + std::to_string(b.updates) + ", \"rows\": " + std::to_string(b.Y.rows()) +
         ", \"rank\": " + std::to_string(r.irls.rank) + ", \"iterations\": " + std::to_string(r.irls.iterations) +
         ", \"outlier_fraction\": " + number(r.irls.outlier_fraction) +
         ", \"with_prior\": " + (with_prior ? "true" : "false") + ", \"huber_k\": " + number(huber_k) + ",\n";
    s += "    \"parameters\": [";
    for (std::size_t k = 0; k < b.names.size(); ++k) s += std::string(k ? ", " : "") + "\"" + b.names[k] + "\"";
    s += "],\n";
    auto vec = [&](const char* name, const Eigen::VectorXd& v, bool comma) {
      s += std::string("    \"") + name + "\": [";
      for (Eigen::Index k = 0; k < v.size(); ++k) s += std::string(k ? ", " : "") + number(v(k));
      s += comma ? "],\n" : "]\n";
    };
    vec("batch", r.irls.theta, true);
    vec("batch_std", r.batch_std, true);
    s += "    \"batch_covariance\": [";
    for (Eigen::Index i = 0; i < r.irls.covariance.rows(); ++i) {
      s += i ? ", [" : "[";
      for (Eigen::Index j = 0; j < r.irls.covariance.cols(); ++j) s += std::string(j ? ", " : "") + number(r.irls.covariance(i, j));
      s += "]";
    }
    s += "],\n";
    vec("online", b.online, true);
    vec("online_std", b.online_std, true);
    vec("prior", b.prior, true);
    vec("prior_std", b.prior_std, false);
    s += e + 1 < results.size() ? "  },\n" : "  }\n";
  }
  return s + "}\n";
}

std::string toText(const std::vector<BatchResult>& results) {
  std::string s;
  char buf[256];
  for (const BatchResult& r : results) {
    const EntityBatch& b = r.batch;
    std::snprintf(buf, sizeof buf, "%s: %ld updates, %ld rows, rank %d of %zu, %d iterations, %.2g %% outliers\n",
                  b.entity.c_str(), b.updates, static_cast<long>(b.Y.rows()), r.irls.rank, b.names.size(),
                  r.irls.iterations, 100.0 * r.irls.outlier_fraction);
    s += buf;
    for (std::size_t k = 0; k < b.names.size(); ++k) {
      const auto i = static_cast<Eigen::Index>(k);
      const double d = r.irls.theta(i) - b.online(i);
      const double sc = std::sqrt(r.batch_std(i) * r.batch_std(i) + b.online_std(i) * b.online_std(i));
      std::snprintf(buf, sizeof buf, "  %-10s batch %12.6g ± %-10.3g online %12.6g ± %-10.3g difference %.3g σ\n",
                    b.names[k].c_str(), r.irls.theta(i), r.batch_std(i), b.online(i), b.online_std(i),
                    sc > 0.0 ? d / sc : 0.0);
      s += buf;
    }
  }
  return s;
}

}  // namespace mrqp::irls
